#pragma once
// Everything a plugin author includes. A library exports its plugins with one line:
//   BRICKYARD_PLUGINS(MyFilter, MyOtherNode)
// where each class derives from brickyard::Plugin and has `static brickyard::Manifest manifest()`.
#include <brickyard/abi.hpp>
#include <brickyard/context.hpp>
#include <brickyard/manifest.hpp>
#include <brickyard/param_binding.hpp>
#include <brickyard/port_binding.hpp>
#include <brickyard/roles.hpp>
#include <brickyard/version.hpp>

namespace brickyard {

// Lifecycle: configure -> activate -> step ... step -> deactivate -> destroyed.
// An exception from any of them fails the node; the host names it and shuts the graph down.
class Plugin {
 public:
  virtual ~Plugin() = default;
  virtual void configure(Context& ctx) {}
  virtual void activate(Context& ctx) {}
  virtual void step(Context& ctx) = 0;
  virtual void deactivate(Context& ctx) {}
};

struct PluginDescriptor {
  Manifest (*manifest)();
  Plugin* (*create)();
  void (*destroy)(Plugin*);  // objects are deleted by the library that made them
};

namespace detail {
template <class P> Plugin* create_plugin() { return new P(); }
template <class P> void destroy_plugin(Plugin* p) { delete p; }
template <class... Ps> const brickyard_library_info* library_info() {
  static const PluginDescriptor descriptors[] = {{&Ps::manifest, &create_plugin<Ps>, &destroy_plugin<Ps>}...};
  static const brickyard_library_info info = {BRICKYARD_ABI_MAJOR, BRICKYARD_ABI_MINOR, BRICKYARD_CXX_ABI_TAG,
                                              static_cast<std::uint32_t>(sizeof...(Ps)), BRICKYARD_SDK_VERSION,
                                              descriptors};
  return &info;
}
}  // namespace detail

}  // namespace brickyard

#define BRICKYARD_PLUGINS(...)                                                                   \
  extern "C" BRICKYARD_EXPORT const brickyard_library_info* brickyard_plugin_library(void) {     \
    return ::brickyard::detail::library_info<__VA_ARGS__>();                                     \
  }
