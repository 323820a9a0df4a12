#!/usr/bin/env bash
# The bash and zsh completions offer what `tumble --help` declares: every subcommand it lists
# (so a new one is checked without an edit here), every option of every `tumble SUB --help`, the
# integrators its --integrator help names, values for --antialias that its help names, *.toml
# files (and folders, not other files) for a scene. bash is run for real (COMP_WORDS, COMPREPLY);
# zsh's _arguments specs are checked as text, as zsh would receive them. Exact: a candidate is
# offered or it is not.
#   completions_cover_help.sh TUMBLE BASH_COMPLETION ZSH_COMPLETION
set -euo pipefail
tumble=$(realpath "$1") bash_file=$(realpath "$2") zsh_file=$(realpath "$3")
source "$(dirname "$0")/help_options.sh"
failures=0
fail() { echo "FAIL: $*" >&2; failures=$((failures + 1)); }

# The candidates bash offers for a command line whose last word is being completed.
bash_complete() {
  bash --norc --noprofile -c 'source "$1"; shift; COMP_WORDS=("$@"); COMP_CWORD=$(($# - 1))
    _tumble; printf "%s\n" "${COMPREPLY[@]}"' _ "$bash_file" "$@"
}
# The words of the --integrator help: "euler | symplectic-euler | ... (overrides the scene)".
integrators=$("$tumble" render --help | sed -n 's/^  --integrator TEXT *//p' | sed 's/ (.*//' |
  tr -d ' ' | tr '|' '\n' | sort)
[ "$(wc -l <<<"$integrators")" -eq 5 ] || fail "--integrator help does not list five: $integrators"

# --- bash
errors=$(bash --norc --noprofile -c 'set -u; source "$1"; complete -p tumble' _ "$bash_file" 2>&1 >/dev/null) ||
  fail "bash cannot source $bash_file: $errors"
[ -z "$errors" ] || fail "sourcing $bash_file prints: $errors"
offered=$(bash_complete "$tumble" -)
for option in --help --version; do
  grep -qxF -- "$option" <<<"$offered" || fail "bash: tumble - does not offer $option"
done
mapfile -t subcommands < <(help_subcommands "$tumble")
[ "$(bash_complete "$tumble" "" | sort)" = "$(printf '%s\n' "${subcommands[@]}" | sort)" ] ||
  fail "bash: 'tumble <TAB>' is not the subcommands of --help (${subcommands[*]})"
for sub in "${subcommands[@]}"; do
  offered=$(bash_complete "$tumble" "$sub" "-")
  for option in $(help_options "$tumble" "$sub"); do
    grep -qxF -- "$option" <<<"$offered" || fail "bash: tumble $sub - does not offer $option"
  done
  if help_options "$tumble" "$sub" | grep -qx -- --integrator &&
    [ "$sub" != study ]; then
    [ "$(bash_complete "$tumble" "$sub" --integrator "" | sort)" = "$integrators" ] ||
      fail "bash: tumble $sub --integrator <TAB> is not the integrators of --help"
  fi
done
antialias_help=$("$tumble" render --help | grep -- '^  --antialias')
offered=$(bash_complete "$tumble" render --antialias "")
[ "$(wc -l <<<"$offered")" -eq 3 ] || fail "bash: --antialias offers $(echo $offered), not three"
for value in $offered; do
  grep -qw -- "$value" <<<"$antialias_help" || fail "bash: --antialias $value is not in its help"
done
grep -qx libx264 <<<"$(bash_complete "$tumble" render --encoder "")" ||
  fail "bash: --encoder does not offer libx264 (tumble info lists it)"
scenes=$(mktemp -d)
trap 'rm -rf "$scenes"' EXIT
mkdir "$scenes/more" && touch "$scenes/drop.toml" "$scenes/notes.txt"
[ "$(cd "$scenes" && bash_complete "$tumble" render "" | sort | tr '\n' ' ')" = "drop.toml more " ] ||
  fail "bash: tumble render <TAB> does not offer exactly the .toml file and the folder"

# --- zsh
zsh -n "$zsh_file" || fail "zsh -n $zsh_file"
zsh_run() { zsh -f -c 'compdef() { :; }; source "$1"; shift; "$@"' _ "$zsh_file" "$@"; }
[ "$(zsh_run _tumble_subcommands "$tumble" | cut -d: -f1 | sort)" = "$(printf '%s\n' "${subcommands[@]}" | sort)" ] ||
  fail "zsh: the subcommands are not those of --help"
for sub in "${subcommands[@]}"; do
  specs=$(zsh_run _tumble_option_specs "$tumble" "$sub")
  for option in $(help_options "$tumble" "$sub"); do
    # "(-q --quiet)-q[Print ...]", "*--still[...]:float: ", "--png[...]": a described spec.
    grep -qE -- "^(\([^)]*\)|\*)?$option\[[^]]+\]" <<<"$specs" ||
      fail "zsh: tumble $sub has no described spec for $option"
  done
  for positional in $(help_positionals "$tumble" "$sub"); do
    grep -qE "^[0-9]+:$positional:" <<<"$specs" || fail "zsh: tumble $sub has no spec for $positional"
  done
done
# The value functions, with _describe replaced by one that prints its candidates.
zsh_values() { zsh -f -c '_describe() { print -l -- ${(P)${@[-1]}}; }; compdef() { :; }
  source "$1"; tumble=$2; $3' _ "$zsh_file" "$tumble" "$1"; }
grep -qx libx264 <<<"$(zsh_values _tumble_encoders)" || fail "zsh: --encoder does not offer libx264"
[ "$(zsh_values _tumble_egl_devices | head -n 1)" = 0 ] || fail "zsh: --egl-device does not offer 0"
action=$(zsh_run _tumble_value_action --integrator | tr -d '()' | tr ' ' '\n' | sort)
[ "$action" = "$integrators" ] || fail "zsh: --integrator values are not the integrators of --help"

if [ "$failures" -gt 0 ]; then
  echo "$failures problem(s) in packaging/completions/" >&2
  exit 1
fi
echo "bash and zsh completions cover ${#subcommands[@]} subcommands: ${subcommands[*]}"
