#!/usr/bin/env bash
# Ports declared once (docs/writing-a-plugin.md): every plugin binds its ports with PortBinding,
# so no plugin source declares a port through Manifest::input/output or an on_input trigger by
# name, nor connects one by name through ctx.input/ctx.output. Exit 1 naming each file and line.
#   ports_declared_once.sh SOURCE_DIR
#   ports_declared_once.sh --self-test SOURCE_DIR SCRATCH   (the check must catch a planted one)
set -u
check() {
  local root=$1 hits
  [ -d "$root/plugins" ] || return 0
  hits=$(grep -rnE --include='*.cpp' --include='*.hpp' \
    '\.(input|output)(<|_any\()|\.on_input\(|ctx\.(input|output)(<|_any\()' "$root/plugins" "$root/sdk/template" "$root/sdk/role_templates" 2>/dev/null)
  [ -z "$hits" ] && return 0
  echo "plugins declaring or connecting a port by name (use PortBinding):"; echo "$hits"
  return 1
}
if [ "${1:-}" = "--self-test" ]; then
  src=$2; scratch=$3
  rm -rf "$scratch"; mkdir -p "$scratch/plugins/acme/x"
  printf '%s\n' '  b.input("in", &Ports::in).steps();' '    .with_ports(ports())' '  io_ = ports().connect(ctx);' > "$scratch/plugins/acme/x/plugin.cpp"
  check "$scratch" > /dev/null || { echo "FAIL: a clean tree was flagged"; exit 1; }
  for planted in '        .input<msgs::Scalar>("in")' '        .output<msgs::Scalar>("out")' '        .on_input("in")' \
                 '        .input_any("in")' '    in_ = ctx.input<msgs::Scalar>("in");' '    out_ = ctx.output_any("out");'; do
    echo "$planted" > "$scratch/plugins/acme/x/bad.cpp"
    check "$scratch" > /dev/null && { echo "FAIL: missed: $planted"; exit 1; }
  done
  check "$src" || exit 1
  echo "port check: catches what it must"
  exit 0
fi
check "$1" || exit 1
echo "plugins: every port declared once"
