#!/usr/bin/env bash
# The house's one rule (docs/architecture.md): nothing car-side includes the simulator. Car side is
# every source folder but plugins/sim: the shared libraries, the framework, the SDK, the tools and
# the car's plugin areas. A violation is an include of a path under sim/, of the simulator's
# adapter headers, or of its world message (the car reads TrackMap), or a car-side CMake file
# linking the simulator's library. Tests may use everything: tests/ and each area's tests/ folder
# are left out. Exit 1 naming each file and line; 0 when clean.
#   car_side_includes.sh SOURCE_DIR
#   car_side_includes.sh --self-test SOURCE_DIR SCRATCH   (the check must catch a planted violation)
set -u
check() {
  local root=$1 bad=0 hits
  local dirs=()
  for d in libs framework sdk tools plugins; do [ -d "$root/$d" ] && dirs+=("$root/$d"); done
  hits=$(grep -rnE --include='*.hpp' --include='*.h' --include='*.cpp' --include='*.cc' --include='*.in' \
           '^[[:space:]]*#[[:space:]]*include[[:space:]]*[<"]([^">]*/)?(sim/[^">]*|world_msg\.hpp|sensor_faults\.hpp|TrackWorld\.h)[">]' \
           "${dirs[@]}" 2>/dev/null | grep -v "^$root/plugins/sim/" | grep -v "^$root/[^:]*/tests/")
  if [ -n "$hits" ]; then
    echo "car-side files include the simulator:"; echo "$hits"; bad=1
  fi
  hits=$(grep -rn --include='CMakeLists.txt' 'brickyard_sim_algorithms' "${dirs[@]}" 2>/dev/null | grep -v "^$root/plugins/sim/")
  if [ -n "$hits" ]; then
    echo "car-side CMake files link the simulator:"; echo "$hits"; bad=1
  fi
  return $bad
}
if [ "${1:-}" = "--self-test" ]; then
  src=$2; scratch=$3
  rm -rf "$scratch"; mkdir -p "$scratch/plugins/planning/common" "$scratch/plugins/sim/common"
  echo '#include "track/track.hpp"' > "$scratch/plugins/planning/common/ok.cpp"
  echo '#include "../../sim/common/track.hpp"' > "$scratch/plugins/sim/common/inside_the_simulator_is_fine.cpp"
  mkdir -p "$scratch/framework/tests"
  echo '#include <brickyard/msgs/TrackWorld.h>' > "$scratch/framework/tests/a_test_may_use_everything.cpp"
  check "$scratch" > /dev/null || { echo "FAIL: a clean tree was flagged"; exit 1; }
  for planted in '#include "../../sim/common/track.hpp"' '#  include <brickyard/msgs/TrackWorld.h>' '#include "world_msg.hpp"'; do
    echo "$planted" > "$scratch/plugins/planning/common/bad.cpp"
    check "$scratch" > /dev/null && { echo "FAIL: missed: $planted"; exit 1; }
  done
  rm "$scratch/plugins/planning/common/bad.cpp"
  echo 'target_link_libraries(x PRIVATE brickyard_sim_algorithms)' > "$scratch/plugins/planning/CMakeLists.txt"
  check "$scratch" > /dev/null && { echo "FAIL: missed a car-side link of the simulator"; exit 1; }
  check "$src" || exit 1
  echo "include check: catches what it must"
  exit 0
fi
check "$1" || exit 1
echo "car side: no simulator include"
