#!/usr/bin/env bash
# Third-party development: install the SDK into a temporary prefix, build sdk/template out of tree
# against it (find_package(brickyard)), run a graph that loads the result; then scaffold a new
# plugin with `brickyard new-plugin`, build it the same way and run it too.
set -eu
build=$1; template=$2; work=$3; domain=$4
rm -rf "$work"; mkdir -p "$work"
prefix=$work/prefix
cmake --install "$build" --prefix "$prefix" > "$work/install.log"
by=$prefix/bin/brickyard
launcher=""
command -v ccache >/dev/null && launcher="-DCMAKE_CXX_COMPILER_LAUNCHER=ccache"

echo "--- template, out of tree"
cp -r "$template" "$work/template"
cmake -S "$work/template" -B "$work/template/build" -G Ninja -DCMAKE_PREFIX_PATH="$prefix" $launcher > "$work/t_cfg.log"
cmake --build "$work/template/build" > "$work/t_build.log"
"$by" run "$work/template/graph.json" --domain "$domain" --out "$work/template_run"
grep -q '"passed": 1.0' "$work/template_run/summary.json"
grep -q '"filtered": 40.0' "$work/template_run/summary.json"

echo "--- new-plugin acme.smoother"
"$by" new-plugin acme.smoother --dir "$work/smoother"
grep -q 'Manifest("acme.smoother"' "$work/smoother/src/plugin.cpp"
cmake -S "$work/smoother" -B "$work/smoother/build" -G Ninja -DCMAKE_PREFIX_PATH="$prefix" $launcher > "$work/s_cfg.log"
cmake --build "$work/smoother/build" > "$work/s_build.log"
"$by" plugins --plugin-path "$work/smoother/build" | grep -q '^acme.smoother 0.1.0'
"$by" run "$work/smoother/graph.json" --domain "$domain" --out "$work/smoother_run"
grep -q '"passed": 1.0' "$work/smoother_run/summary.json"
echo "installed SDK builds and runs third-party plugins"
