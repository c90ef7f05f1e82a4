#!/usr/bin/env bash
# The shell completions (completions/): bash's function fills COMPREPLY for typical command
# lines, zsh's turns `camgen --help` into _arguments specs and offers the machines of
# `camgen --list-machines`. Usage: completion.sh CAMGEN SOURCE_DIR [BASH_COMPLETION_FILE]
# (the file defaults to SOURCE_DIR/completions/camgen.bash; scripts/test-install passes the
# installed one). Fails, and says why, when zsh is missing (scripts/install-deps --tests installs it).
set -euo pipefail
camgen=$(realpath "$1")
source_dir=$(cd "$2" && pwd)
bash_file=${3:-$source_dir/completions/camgen.bash}
scratch=$(mktemp -d)
trap 'rm -rf "$scratch"' EXIT
failures=0
fail() { echo "completion: $*" >&2; failures=$((failures + 1)); }

# Only the machines this test gives: none of the user's running it.
unset CAMGEN_MACHINES
export XDG_CONFIG_HOME=$scratch/config
# A machine of the user's (issue 14 part 2): completion asks the program, it has no list of
# its own.
mkdir "$scratch/machines"
echo '{"extends": "fanuc", "description": "our Fanuc with sequence numbers"}' >"$scratch/machines/fanuc-shop.json"

# Completes the words given (the last one is the word being completed) and prints COMPREPLY.
complete_bash() {
  bash -c 'source "$1"; shift; COMP_WORDS=("$@"); COMP_CWORD=$((${#COMP_WORDS[@]} - 1)); _camgen
           printf "%s\n" "${COMPREPLY[@]}"' _ "$bash_file" "$@" | sort | tr '\n' ' '
}
expect_bash() {
  local want=$1
  shift
  local got
  got=$(cd "$scratch" && complete_bash "$@")
  [ "$got" = "$want" ] || fail "bash: [$*] completes to [$got], expected [$want]"
}
mkdir -p "$scratch/jobs"
touch "$scratch/jobs/plate.json" "$scratch/jobs/plate.nc"
expect_bash "fanuc fanuc-lathe " "$camgen" --machine fa
expect_bash "fanuc fanuc-lathe " "$camgen" -m fa
expect_bash "fanuc fanuc-lathe " "$camgen" --describe-machine fa
CAMGEN_MACHINES=$scratch/machines expect_bash "fanuc fanuc-lathe fanuc-shop " "$camgen" --machine fa
expect_bash "--machine --max-elements --max-holes " "$camgen" --ma
expect_bash "--job " "$camgen" verify --j
expect_bash "job machine tools " "$camgen" schema ""
expect_bash "inch " "$camgen" --units i
expect_bash "jobs/plate.json " "$camgen" jobs/pl
expect_bash "jobs/plate.json jobs/plate.nc " "$camgen" verify jobs/pl
# Every option --help lists is offered after "-".
for option in $("$camgen" --help | sed -n 's/^ \{1,\}\(-[^ ]*\).*/\1/p' | tr ',' ' '); do
  case " $(complete_bash "$camgen" -) " in *" $option "*) ;; *) fail "bash: $option is not offered after -" ;; esac
done

if ! command -v zsh >/dev/null; then
  fail "zsh is not installed (scripts/install-deps --tests installs it)"
else
  # zsh's completion system stubbed: what _camgen hands to _arguments and _describe.
  zsh_out=$(CAMGEN_MACHINES=$scratch/machines zsh -f -c '
    _call_program() { shift; eval "$@"; }
    _arguments() { print -l -- "$@"; }
    _describe() { print -l -- "${(@P)4}"; }
    _files() { }
    fpath=("$1" $fpath)
    autoload -U _camgen
    words=("$2" --machine fa); CURRENT=3
    _camgen
    _camgen_machines
    words=("$2" verify --); CURRENT=3
    _camgen' _ "$source_dir/completions" "$camgen")
  for want in '(-m --machine)--machine=[Machine name (see --list-machines) or path to a machine JSON file]:machine:_camgen_machines' \
              '(--units)--units=[Output units, overriding the machine file]:units:(mm inch)' \
              '(--job)--job=[The job the program should carry out]:job:_files -g "*.json(-.)"' \
              'fanuc:Generic Fanuc-style ISO mill (0i/18i): G81-G86/G89, G73, G74 canned cycles, P in ms' \
              'fanuc-shop:our Fanuc with sequence numbers' '1: :_camgen_first' '1:NC program:_files'; do
    # A machine's line goes on with where it comes from ("  [built-in]").
    awk -v want="$want" 'index($0, want) == 1 { found = 1 } END { exit !found }' <<<"$zsh_out" ||
      fail "zsh: no [$want] in what _camgen passes on"
  done
  for option in $("$camgen" --help | sed -n 's/^ \{1,\}\(-[^ ]*\).*/\1/p' | tr ',' ' '); do
    grep -q -- "^([^)]*)$option[=+[]" <<<"$zsh_out" || fail "zsh: no spec for $option"
  done
fi
[ "$failures" -eq 0 ] || exit 1
echo "completion: bash and zsh complete options, machine names (the user's too) and files"
