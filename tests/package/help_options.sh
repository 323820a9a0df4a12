# Sourced by the package tests: what `tumble --help` declares, read the same way the man page
# generator and the completions read it.
#   help_subcommands TUMBLE      one subcommand per line, from the "Subcommands:" list
#   help_options TUMBLE SUB      every option name of `tumble SUB --help` (-x and --long), one a line
#   help_positionals TUMBLE SUB  the positional argument names of `tumble SUB --help`

help_subcommands() {
  "$1" --help | awk '/^Subcommands:/ {on = 1; next} on && /^  [a-z]/ {print $1}'
}

help_options() {
  "$1" "$2" --help | awk '/^Options:/ {on = 1; next} /^[A-Z][a-z]*:/ {on = 0}
    on && /^  +-/ {n = split($1, names, ","); for (i = 1; i <= n; i++) print names[i]}'
}

help_positionals() {
  "$1" "$2" --help | awk '/^Positionals:/ {on = 1; next} /^[A-Z][a-z]*:/ {on = 0}
    on && /^  +[a-z]/ {print $1}'
}
