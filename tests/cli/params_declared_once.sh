#!/usr/bin/env bash
# Parameters declared once (docs/writing-a-plugin.md): every plugin binds its parameters with
# ParamBinding, so no plugin source declares a ParamSpec through Manifest::param() or reads a value
# by name from ctx.params() other than through a binding's read(). (A ParamSpec handed to
# bind_with/declare, and the reader beside it, are the binding's own escape hatch and allowed.)
# Exit 1 naming each file and line; 0 when clean.
#   params_declared_once.sh SOURCE_DIR
#   params_declared_once.sh --self-test SOURCE_DIR SCRATCH   (the check must catch a planted one)
set -u
check() {
  local root=$1 bad=0 hits
  [ -d "$root/plugins" ] || return 0
  hits=$(grep -rnE --include='*.cpp' --include='*.hpp' '\.param\([[:space:]]*(ParamSpec|plugins::)' "$root/plugins" "$root/sdk/template" "$root/sdk/role_templates" 2>/dev/null)
  if [ -n "$hits" ]; then
    echo "plugins declaring a parameter apart from its read (use ParamBinding):"; echo "$hits"; bad=1
  fi
  hits=$(grep -rnE --include='*.cpp' --include='*.hpp' 'ctx\.params\(\)' "$root/plugins" "$root/sdk/template" "$root/sdk/role_templates" 2>/dev/null |
         grep -vE '\.read\([[:space:]]*ctx\.params\(\)[[:space:]]*\)')
  if [ -n "$hits" ]; then
    echo "plugins reading parameters by name (use ParamBinding::read):"; echo "$hits"; bad=1
  fi
  return $bad
}
if [ "${1:-}" = "--self-test" ]; then
  src=$2; scratch=$3
  rm -rf "$scratch"; mkdir -p "$scratch/plugins/acme/x"
  printf '%s\n' '    .parameters(bindings())' '  const Settings s = bindings().read(ctx.params());' > "$scratch/plugins/acme/x/plugin.cpp"
  check "$scratch" > /dev/null || { echo "FAIL: a clean tree was flagged"; exit 1; }
  for planted in '        .param(ParamSpec::number("gain", 1.0))' '    gain_ = ctx.params().number("gain");' \
                 '    const Params& p = ctx.params();' '        .param(plugins::vehicle_param())'; do
    echo "$planted" > "$scratch/plugins/acme/x/bad.cpp"
    check "$scratch" > /dev/null && { echo "FAIL: missed: $planted"; exit 1; }
  done
  check "$src" || exit 1
  echo "parameter check: catches what it must"
  exit 0
fi
check "$1" || exit 1
echo "plugins: every parameter declared once"
