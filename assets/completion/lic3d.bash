# SPDX-License-Identifier: BSD-3-Clause
# Bash completion for lic3d and lic3d-view. The commands are completed, and the flags and the
# choices of each flag are read from the program's own --help (`lic3d render --help`) at the
# moment of completing, so they follow the installed version; other words complete file names.
# Installed as share/bash-completion/completions/lic3d and .../lic3d-view.

# The lines of the help that describe FLAG: its own line and the ones that continue it.
_lic3d_flag_help() {
    awk -v flag="$1" '
        /^ *-/ {
            found = 0
            n = split($1, names, ",")
            for (i = 1; i <= n; i++) if (names[i] == flag) found = 1
        }
        /^[^ ]/ { found = 0 }
        found { print }'
}

_lic3d() {
    local cur=${COMP_WORDS[COMP_CWORD]} prev="" program=${COMP_WORDS[0]} command="" i
    local commands="devices compute render render2d bench view"
    ((COMP_CWORD > 0)) && prev=${COMP_WORDS[COMP_CWORD - 1]}
    # --flag=value: bash splits at "=".
    if [[ $cur == "=" ]]; then
        cur=""
    elif [[ $prev == "=" ]] && ((COMP_CWORD > 1)); then
        prev=${COMP_WORDS[COMP_CWORD - 2]}
    fi
    if [[ ${program##*/} == lic3d ]]; then
        for ((i = 1; i < COMP_CWORD; i++)); do
            if [[ " $commands " == *" ${COMP_WORDS[i]} "* ]]; then
                command=${COMP_WORDS[i]}
                break
            fi
        done
    fi

    local help
    help=$("$program" ${command:+"$command"} --help 2>/dev/null) || help=""
    COMPREPLY=()

    # A value after a flag that takes one (its type, TEXT, INT, ENUM..., follows it on its line).
    if [[ $prev == -* ]]; then
        local entry
        entry=$(printf '%s\n' "$help" | _lic3d_flag_help "$prev")
        if [[ $entry =~ ^\ +[-A-Za-z0-9,]+\ [A-Z] ]]; then
            # Choices: TEXT:{a,b,c}, or ENUM with "a|b|c" ending its description.
            local choices=""
            if [[ ${entry%%$'\n'*} =~ :\{([^}]*)\} ]]; then
                choices=${BASH_REMATCH[1]//,/ }
            elif [[ $entry == *" ENUM"* ]]; then
                choices=$(printf '%s' "$entry" | tr -s ' \n' '  ' |
                    grep -oE '[A-Za-z0-9._-]+(\|[A-Za-z0-9._-]+)+ *$')
                choices=${choices//|/ }
            fi
            if [[ -n $choices ]]; then
                mapfile -t COMPREPLY < <(compgen -W "$choices" -- "$cur")
            else
                compopt -o filenames 2>/dev/null
                mapfile -t COMPREPLY < <(compgen -f -- "$cur")
            fi
            return 0
        fi
    fi

    if [[ $cur == -* ]]; then
        local flags
        flags=$(printf '%s\n' "$help" |
            sed -n 's/^ *\(-[A-Za-z0-9],\)\{0,1\}\(--[A-Za-z0-9][A-Za-z0-9-]*\).*/\2/p')
        mapfile -t COMPREPLY < <(compgen -W "$flags" -- "$cur")
    elif [[ ${program##*/} == lic3d && -z $command ]]; then
        mapfile -t COMPREPLY < <(compgen -W "$commands" -- "$cur")
    else
        compopt -o filenames 2>/dev/null
        mapfile -t COMPREPLY < <(compgen -f -- "$cur")
    fi
    return 0
}

complete -F _lic3d lic3d lic3d-view
