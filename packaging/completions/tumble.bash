# bash completion for tumble(1): subcommands, options, their values, scene files.
#
# Subcommands and options are read from the binary's own --help (the same source as the man
# page) when first needed and kept for the shell session, so they always match the tumble being
# completed. Values: integrators, anti-aliasing modes and MSAA samples; H.264 encoders and EGL
# devices from `tumble info` (asked once, only when those values are completed); *.toml files for
# a positional whose help says TOML, any file otherwise.
# Installed as share/bash-completion/completions/tumble; needs no bash-completion helpers.

declare -gA _tumble_help_cache=()

# `tumble [SUB] --help`, asked once per binary and subcommand.
_tumble_help() {
  local key="$1|$2"
  if [[ -z ${_tumble_help_cache[$key]+set} ]]; then
    _tumble_help_cache[$key]=$("$1" ${2:+"$2"} --help 2>/dev/null)
  fi
  printf '%s\n' "${_tumble_help_cache[$key]}"
}

_tumble_subcommands() {
  _tumble_help "$1" "" | awk '/^Subcommands:/ {on = 1; next} on && /^  [a-z]/ {print $1}'
}

# Every option of `tumble SUB --help`; with "values", only those that take a value (TEXT, INT...).
_tumble_options() {
  _tumble_help "$1" "$2" | awk -v values="$3" '/^Options:/ {on = 1; next} /^[A-Z][a-z]*:/ {on = 0}
    on && /^  +-/ { if (values != "" && $2 !~ /^[A-Z]+$/) next
                    n = split($1, names, ","); for (i = 1; i <= n; i++) print names[i] }'
}

# The positional arguments' help lines of `tumble SUB --help`.
_tumble_positionals() {
  _tumble_help "$1" "$2" | awk '/^Positionals:/ {on = 1; next} /^[A-Z][a-z]*:/ {on = 0}
    on && /^  +[a-z]/ {print}'
}

# From `tumble info` (it opens a GL context: about 0.1-0.3 s), once per session.
_tumble_info() {
  if [[ -z ${_tumble_help_cache[$1|info]+set} ]]; then
    _tumble_help_cache[$1|info]=$("$1" info 2>/dev/null)
  fi
  printf '%s\n' "${_tumble_help_cache[$1|info]}"
}

_tumble() {
  local cur=${COMP_WORDS[COMP_CWORD]} prev=${COMP_WORDS[COMP_CWORD - 1]}
  local tumble=${COMP_WORDS[0]} sub="" i positional=0
  COMPREPLY=()
  # The subcommand is the first word that is not an option.
  for ((i = 1; i < COMP_CWORD; i++)); do
    if [[ ${COMP_WORDS[i]} != -* ]]; then sub=${COMP_WORDS[i]}; break; fi
  done
  if [[ -z $sub ]]; then
    if [[ $cur == -* ]]; then
      COMPREPLY=($(compgen -W "--help --version" -- "$cur"))
    else
      COMPREPLY=($(compgen -W "$(_tumble_subcommands "$tumble")" -- "$cur"))
    fi
    return
  fi

  # The value of an option.
  case $prev in
    --integrator)
      COMPREPLY=($(compgen -W "euler symplectic-euler midpoint rk4 adaptive" -- "$cur")); return ;;
    --integrators)  # a comma-separated list: complete its last element
      local head="" tail=$cur
      if [[ $cur == *,* ]]; then head=${cur%,*},; tail=${cur##*,}; fi
      COMPREPLY=($(compgen -P "$head" -W "euler symplectic-euler midpoint rk4 adaptive" -- "$tail"))
      compopt -o nospace 2>/dev/null
      return ;;
    --antialias) COMPREPLY=($(compgen -W "fxaa msaa none" -- "$cur")); return ;;
    --msaa) COMPREPLY=($(compgen -W "0 2 4" -- "$cur")); return ;;
    --size) COMPREPLY=($(compgen -W "1280x720 1920x1080 640x360 320x240 160x120" -- "$cur")); return ;;
    --encoder)
      local encoders
      encoders=$(_tumble_info "$tumble" | sed -n 's/^H.264 encoders in FFmpeg://p')
      COMPREPLY=($(compgen -W "auto $encoders" -- "$cur")); return ;;
    --egl-device)
      local count
      count=$(_tumble_info "$tumble" | sed -n 's/^EGL devices: \([0-9]*\)$/\1/p')
      [[ ${count:-0} -gt 0 ]] && COMPREPLY=($(compgen -W "$(seq 0 $((count - 1)))" -- "$cur"))
      return ;;
    --out)
      compopt -o filenames 2>/dev/null
      COMPREPLY=($(compgen -d -- "$cur")); return ;;
    --diff-out)
      compopt -o filenames 2>/dev/null
      COMPREPLY=($(compgen -f -- "$cur")); return ;;
  esac
  if [[ $prev == -* ]] && _tumble_options "$tumble" "$sub" values | grep -qxF -- "$prev"; then
    return  # a number or a text of the user's: nothing to offer
  fi

  if [[ $cur == -* ]]; then
    COMPREPLY=($(compgen -W "$(_tumble_options "$tumble" "$sub")" -- "$cur"))
    return
  fi
  # A positional argument: scene files where the help says TOML, else any file or folder.
  compopt -o filenames 2>/dev/null
  if _tumble_positionals "$tumble" "$sub" | grep -q TOML; then
    COMPREPLY=($(compgen -f -X '!*.toml' -- "$cur") $(compgen -d -- "$cur"))
  else
    COMPREPLY=($(compgen -f -- "$cur"))
  fi
}

complete -F _tumble tumble
