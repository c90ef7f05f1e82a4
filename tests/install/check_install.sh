#!/usr/bin/env bash
# `cmake --install` into a scratch prefix: every file where it belongs, the installed camgen
# run from another folder reads the machine files installed beside it (and falls back to its
# compiled-in copies without them), the installed headers include nothing that is not
# installed. Usage: check_install.sh BUILD_DIR SOURCE_DIR
set -euo pipefail
build=$(cd "$1" && pwd)
source_dir=$(cd "$2" && pwd)
scratch=$(mktemp -d)
trap 'rm -rf "$scratch"' EXIT
prefix=$scratch/prefix
fail() { echo "check_install: $*" >&2; exit 1; }
# Only the built-in machines: none of the user's running it.
unset CAMGEN_MACHINES
export XDG_CONFIG_HOME=$scratch/config

cmake --install "$build" --prefix "$prefix" >/dev/null
camgen=$prefix/bin/camgen
[ -x "$camgen" ] || fail "no bin/camgen"

# The machine files, schemas, man page and completions.
for f in "$source_dir"/machines/*.json; do
  cmp -s "$f" "$prefix/share/camgen/machines/$(basename "$f")" || fail "machine file $(basename "$f") not installed"
done
for s in job machine tools; do
  "$camgen" schema $s | cmp -s - "$prefix/share/camgen/schema/$s.schema.json" || fail "schema/$s.schema.json is not camgen schema $s"
done
"$camgen" --man | cmp -s - "$prefix/share/man/man1/camgen.1" || fail "camgen.1 is not camgen --man"
[ -f "$prefix/share/bash-completion/completions/camgen" ] || fail "no bash completion"
[ -f "$prefix/share/zsh/vendor-completions/_camgen" ] || fail "no zsh completion"

# The library: static library, CMake package, public headers only.
ls "$prefix"/lib*/libcamgen.a >/dev/null 2>&1 || ls "$prefix"/lib/*/libcamgen.a >/dev/null 2>&1 || fail "no libcamgen.a"
find "$prefix" -name camgenConfig.cmake | grep -q . || fail "no camgenConfig.cmake"
headers=$(cd "$prefix/include" && find . -name '*.hpp' | sed 's|^\./||' | sort)
expected=$(cd "$source_dir/include" && find camgen -name '*.hpp' | sort)
[ "$headers" = "$expected" ] || fail "installed headers differ from include/camgen/: $(diff <(echo "$expected") <(echo "$headers"))"
while read -r header; do
  while read -r included; do
    [ -f "$prefix/include/$included" ] || fail "$header includes \"$included\", which is not installed (an internal header)"
  done < <(sed -n 's/^[[:space:]]*#[[:space:]]*include[[:space:]]*"\([^"]*\)".*/\1/p' "$prefix/include/$header")
done <<< "$headers"

# Run from another folder, through a symlink: the installed machine files are used.
mkdir "$scratch/elsewhere"
ln -s "$camgen" "$scratch/elsewhere/camgen-link"
cd "$scratch/elsewhere"
"$camgen" -q "$source_dir/samples/plate.json" --machine wabeco >installed.knc
"$build/camgen" -q "$source_dir/samples/plate.json" --machine wabeco >built.knc
cmp -s installed.knc built.knc || fail "the installed camgen posts plate.json differently from the built one"
sed -i 's/"description": "[^"]*"/"description": "installed copy, edited"/' "$prefix/share/camgen/machines/wabeco.json"
grep -q 'installed copy, edited' "$prefix/share/camgen/machines/wabeco.json" || fail "test setup: wabeco.json has no description"
for exe in "$camgen" ./camgen-link; do
  "$exe" --list-machines | grep -Fq "installed copy, edited  [built-in, $prefix/share/camgen/machines/wabeco.json]" ||
    fail "$exe --list-machines does not read $prefix/share/camgen/machines/wabeco.json"
done
# Without the installed folder: the compiled-in machines.
rm -r "$prefix/share/camgen/machines"
"$camgen" --list-machines | grep -Eq '^wabeco +Wabeco mill.*  \[built-in\]$' || fail "no fallback to the compiled-in machines"
"$camgen" -q "$source_dir/samples/plate.json" --machine wabeco | cmp -s - built.knc || fail "the fallback posts differently"
echo "check_install: installed layout, machine lookup beside the executable and public headers all right"
