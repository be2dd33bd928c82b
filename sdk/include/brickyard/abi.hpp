#pragma once
// The binary boundary between the host and a plugin library. Only this C struct is read
// before the ABI check passes; everything C++ is touched after it.
#include <cstdint>

// 3.0: Manifest::roles appended (Manifest::plays, brickyard/roles.hpp); ports declared once
//      through PortBinding (brickyard/port_binding.hpp). 2.x plugins must be rebuilt.
// 3.1: Context::wake_on_readable and Trigger::Kind::readable (a driver woken by its device).
// 2.0: Manifest::constraints appended (its layout changed: 1.x plugins must be rebuilt).
// 2.1: TriggerSpec::Kind::latency (Manifest::delivered_after).
// 2.2: TriggerSpec::Kind::deadline (Manifest::step_deadline).
// 2.3: ports of any type (Manifest::input_any/output_any, Context::input_any/output_any,
//      InputChannel and OutputChannel::wire_type/wire_idl).
// 2.4: Manifest::checker appended (Manifest::check, CheckView): a plugin's own checks at
//      validation. The host ignores the field in an older plugin's manifest, which lacks it.
// 2.x and 1.x history: 1.1 Context::find_file and BadInput; 1.2 Context::status.
#define BRICKYARD_ABI_MAJOR 3u
#define BRICKYARD_ABI_MINOR 1u
#define BRICKYARD_ENTRY_POINT_NAME "brickyard_plugin_library"
#define BRICKYARD_EXPORT __attribute__((visibility("default")))

// Host and plugins exchange std::string, std::vector and virtual classes after the check:
// they must agree on the C++ standard library ABI too.
#if defined(_GLIBCXX_USE_CXX11_ABI)
#define BRICKYARD_CXX_ABI_TAG (0x10000u | (_GLIBCXX_USE_CXX11_ABI ? 1u : 0u))
#else
#define BRICKYARD_CXX_ABI_TAG 0x20000u
#endif

extern "C" {

struct brickyard_library_info {
  std::uint32_t abi_major;     // must equal the host's BRICKYARD_ABI_MAJOR
  std::uint32_t abi_minor;     // may be lower than the host's
  std::uint32_t cxx_abi;       // BRICKYARD_CXX_ABI_TAG of the plugin's build
  std::uint32_t plugin_count;
  const char* sdk_version;     // SDK version the library was built against
  const void* plugins;         // const brickyard::PluginDescriptor[plugin_count]
};

typedef const brickyard_library_info* (*brickyard_entry_point)(void);
}
