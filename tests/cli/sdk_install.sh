#!/usr/bin/env bash
# Third-party development: install the SDK into a temporary prefix, build sdk/template out of tree
# against it (find_package(brickyard)), run its own CTest suite (unit tests and graph tests) and a
# graph that loads the result; check the plugin does not link Fast DDS and that the installed SDK
# holds no host-only header; then scaffold a new plugin with `brickyard new-plugin`, build and test
# it the same way; then a planner from `new-plugin --role planner`, raced in configs/race.json with
# --set planner.plugin= and no other edit. A plain install leaves the simulator's plugins out (their
# own component, installed next for the race).
set -eu
build=$1; template=$2; work=$3; domain=$4; with_sim=${5:-ON}  # OFF: a BRICKYARD_SIM=OFF build, no race
rm -rf "$work"; mkdir -p "$work"
prefix=$work/prefix
cmake --install "$build" --prefix "$prefix" > "$work/install.log"
by=$prefix/bin/brickyard
launcher=""
command -v ccache >/dev/null && launcher="-DCMAKE_CXX_COMPILER_LAUNCHER=ccache"

echo "--- installed SDK: public headers only"
for f in brickyard/msgs/registry.hpp brickyard/msgs/ScalarPubSubTypes.h; do
  [ ! -e "$prefix/include/$f" ] || { echo "FAIL: host-only header installed: include/$f"; exit 1; }
done
[ -e "$prefix/include/brickyard/msgs/Scalar.h" ] || { echo "FAIL: include/brickyard/msgs/Scalar.h not installed"; exit 1; }
if grep -rq fastrtps "$prefix"/lib/cmake/brickyard/; then
  echo "FAIL: the CMake package mentions fastrtps:"; grep -rn fastrtps "$prefix"/lib/cmake/brickyard/; exit 1
fi

# Builds a plugin project out of tree, runs its CTest suite, checks its plugin's link.
build_and_test() {  # <project dir> <log prefix> <plugin library name>
  local dir=$1 log=$2 lib=$3
  cmake -S "$dir" -B "$dir/build" -G Ninja -DCMAKE_PREFIX_PATH="$prefix" $launcher \
        "-DBRICKYARD_GRAPH_TEST_ARGS=--domain;$domain" > "$work/${log}_cfg.log"
  grep -q '^CMAKE_BUILD_TYPE:STRING=Release$' "$dir/build/CMakeCache.txt" || { echo "FAIL: $dir: not a Release build by default"; exit 1; }
  cmake --build "$dir/build" > "$work/${log}_build.log"
  ctest --test-dir "$dir/build" --output-on-failure > "$work/${log}_ctest.log" 2>&1 || { cat "$work/${log}_ctest.log"; exit 1; }
  grep -q '100% tests passed' "$work/${log}_ctest.log" || { cat "$work/${log}_ctest.log"; exit 1; }
  # Both kinds ran: the unit tests (GoogleTest, discovered) and the graph tests.
  ctest --test-dir "$dir/build" -N -L brickyard_graph | grep -q 'Total Tests: 2' || { echo "FAIL: $dir: expected 2 graph tests"; exit 1; }
  ctest --test-dir "$dir/build" -N -LE brickyard_graph | grep -Eq 'Total Tests: ([5-9]|[1-9][0-9])' || { echo "FAIL: $dir: the unit tests are missing"; exit 1; }
  sed -n '/tests passed/,$p' "$work/${log}_ctest.log"
  # Only the SDK's message library: no Fast DDS (libfastrtps) in what the plugin links.
  local so=$dir/build/$lib
  readelf -d "$so" > "$work/${log}_readelf.txt"
  grep -q 'NEEDED.*\[libbrickyard_msgs\.so' "$work/${log}_readelf.txt" || { echo "FAIL: $so does not link libbrickyard_msgs"; exit 1; }
  if grep -Eq 'NEEDED.*\[lib(fastrtps|fastdds|brickyard_msgs_dds)' "$work/${log}_readelf.txt"; then
    echo "FAIL: $so links Fast DDS:"; grep NEEDED "$work/${log}_readelf.txt"; exit 1
  fi
  if grep 'LINK_LIBRARIES' "$dir/build/build.ninja" | grep -q 'fastrtps\|fastdds'; then
    echo "FAIL: $dir: Fast DDS on a link line:"; grep 'LINK_LIBRARIES' "$dir/build/build.ninja" | grep 'fastrtps\|fastdds'; exit 1
  fi
}

echo "--- template, out of tree"
diff -r --exclude=build "$template" "$prefix/share/brickyard/template" || { echo "FAIL: the installed template differs from $template"; exit 1; }
cp -r "$prefix/share/brickyard/template" "$work/template"
build_and_test "$work/template" t libmy_plugin.so
"$by" run "$work/template/graph.json" --domain "$domain" --out "$work/template_run"
grep -q '"passed": 1.0' "$work/template_run/summary.json"
grep -q '"filtered": 40.0' "$work/template_run/summary.json"

echo "--- new-plugin acme.smoother"
"$by" new-plugin acme.smoother --dir "$work/smoother"
grep -q 'Manifest("acme.smoother"' "$work/smoother/src/plugin.cpp"
# Every file of the (installed) template, scaffolded.
(cd "$prefix/share/brickyard/template" && find . -type f | sort) > "$work/template_files.txt"
(cd "$work/smoother" && find . -type f | sort) > "$work/smoother_files.txt"
diff "$work/template_files.txt" "$work/smoother_files.txt" || { echo "FAIL: new-plugin did not copy the whole template"; exit 1; }
build_and_test "$work/smoother" s libsmoother.so
ctest --test-dir "$work/smoother/build" -N | grep -q 'smoother.lags_a_step' || { echo "FAIL: graph test not renamed"; exit 1; }
"$by" plugins --plugin-path "$work/smoother/build" | grep -q '^acme.smoother 0.1.0'
"$by" run "$work/smoother/graph.json" --domain "$domain" --out "$work/smoother_run"
grep -q '"passed": 1.0' "$work/smoother_run/summary.json"

echo "--- a plain install: the SDK and the car stack, not the simulator"
ls "$prefix/lib/brickyard/plugins" > "$work/plugins_plain.txt"
grep -q '^libtesting_assert_sink\.so$' "$work/plugins_plain.txt" || { echo "FAIL: testing plugins not installed"; exit 1; }
grep -q '^libplanning_road_graph\.so$' "$work/plugins_plain.txt" || { echo "FAIL: the car stack's plugins not installed"; exit 1; }
if grep -q '^libsim_' "$work/plugins_plain.txt"; then echo "FAIL: a plain install holds the simulator's plugins:"; grep '^libsim_' "$work/plugins_plain.txt"; exit 1; fi
du -sm "$prefix" | awk '{ print "installed, plain: " $1 " MiB" }'
if [ "$with_sim" = ON ]; then
  cmake --install "$build" --prefix "$prefix" --component sim > "$work/install_sim.log"
  [ -e "$prefix/lib/brickyard/plugins/libsim_world.so" ] || { echo "FAIL: --component sim did not install the simulator"; exit 1; }
  du -sm "$prefix" | awk '{ print "installed, with the simulator: " $1 " MiB" }'
fi

echo "--- new-plugin acme.centre_line --role planner, raced in configs/race.json"
if "$by" new-plugin acme.nope --role no_such_role --dir "$work/nope" > "$work/nope.log" 2>&1; then echo "FAIL: an unknown role scaffolded"; exit 1; fi
"$by" new-plugin acme.centre_line --role planner --dir "$work/centre"
grep -q 'Manifest("acme.centre_line"' "$work/centre/src/plugin.cpp"
grep -q 'plays(roles::planner)' "$work/centre/src/plugin.cpp"
build_and_test "$work/centre" c libcentre_line.so
"$by" plugins acme.centre_line --plugin-path "$work/centre/build" | grep -q '^  plays planner$' || { echo "FAIL: acme.centre_line does not play planner"; exit 1; }
if [ "$with_sim" != ON ]; then echo "installed SDK builds and tests third-party plugins (no simulator: no race)"; exit 0; fi
src=$(cd "$template/../.." && pwd)
"$by" run "$src/configs/race.json" --plugin-path "$work/centre/build" --set planner.plugin=acme.centre_line \
  --domain "$domain" --quiet --out "$work/centre_race" > "$work/centre_race.log" 2>&1 || { tail -20 "$work/centre_race.log"; echo "FAIL: the race with acme.centre_line"; exit 1; }
grep 'success' "$work/centre_race.log"
grep -q "node 'referee' finished the run: 2 laps completed" "$work/centre_race.log" || { echo "FAIL: the race did not finish its laps"; exit 1; }
echo "installed SDK builds and tests third-party plugins"
