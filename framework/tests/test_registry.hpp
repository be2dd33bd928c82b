#pragma once
// The testing plugins, loaded the way the host loads them: what unit tests resolve graphs against.
#include "loader/registry.hpp"

namespace brickyard::fw::test {

inline const Registry& testing_plugins() {
  static Registry r = [] {
    Registry x;
    x.add_directory(BRICKYARD_TEST_PLUGIN_DIR);
    return x;
  }();
  return r;
}

}  // namespace brickyard::fw::test
