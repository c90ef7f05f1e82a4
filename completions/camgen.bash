# bash completion for camgen. Options come from `camgen --help` (of the subcommand being
# completed), so they follow the program; machine names from `camgen --list-machines` (each
# line starts with a name), so a user's own machines are offered too; jobs are *.json files.
# Installed as bash-completion's completions/camgen; it needs nothing of bash-completion.

# The machine names camgen knows. $1: the camgen being completed.
_camgen_machines() {
    "$1" --list-machines 2>/dev/null | while IFS=$' \t' read -r name _; do printf '%s\n' "$name"; done
}

# The options of camgen (or of its subcommand $2) as --help lists them. $1: the camgen.
_camgen_options() {
    "$1" ${2:+"$2"} --help 2>/dev/null | sed -n 's/^ \{1,\}\(-[^ ]*\).*/\1/p' | tr ',' '\n'
}

# Adds the files matching $2 (a glob: '*.json', or '*' for any) and the folders to COMPREPLY.
_camgen_files() {
    local IFS=$'\n'
    compopt -o filenames 2>/dev/null
    COMPREPLY+=($(compgen -d -- "$1"))
    if [[ $2 == '*' ]]; then
        COMPREPLY+=($(compgen -f -- "$1"))
    else
        COMPREPLY+=($(compgen -f -X "!$2" -- "$1"))
    fi
}

_camgen() {
    local cur=${COMP_WORDS[COMP_CWORD]} prev='' camgen=${COMP_WORDS[0]} sub='' word i
    ((COMP_CWORD > 0)) && prev=${COMP_WORDS[COMP_CWORD - 1]}
    # --machine=fa: bash splits at '=', so the option is one word further back.
    if [[ $cur == '=' ]]; then
        prev=${COMP_WORDS[COMP_CWORD - 1]}
        cur=''
    elif [[ $prev == '=' ]] && ((COMP_CWORD > 1)); then
        prev=${COMP_WORDS[COMP_CWORD - 2]}
    fi
    [[ $camgen == camgen || -x $camgen ]] || camgen=camgen
    for ((i = 1; i < COMP_CWORD; i++)); do
        word=${COMP_WORDS[i]}
        if [[ $word == verify || $word == schema ]]; then
            sub=$word
            break
        fi
    done
    COMPREPLY=()
    case $prev in
    -m | --machine | --describe-machine)
        local IFS=$'\n'
        COMPREPLY=($(compgen -W "$(_camgen_machines "$camgen")" -- "$cur"))
        # A machine may also be given as the path of its file.
        [[ $cur == */* || $cur == .* ]] && _camgen_files "$cur" '*.json'
        return 0
        ;;
    -o | --output | --plot | --tool-table)
        _camgen_files "$cur" '*'
        return 0
        ;;
    --job)
        _camgen_files "$cur" '*.json'
        return 0
        ;;
    --units | --tool-table-units)
        COMPREPLY=($(compgen -W 'mm inch' -- "$cur"))
        return 0
        ;;
    --max-holes | --max-elements)
        return 0
        ;;
    esac
    if [[ $cur == -* ]]; then
        COMPREPLY=($(compgen -W "$(_camgen_options "$camgen" "$sub")" -- "$cur"))
        return 0
    fi
    case $sub in
    schema) COMPREPLY=($(compgen -W 'job machine tools' -- "$cur")) ;;
    verify) _camgen_files "$cur" '*' ;;
    *)
        COMPREPLY=($(compgen -W 'verify schema' -- "$cur"))
        _camgen_files "$cur" '*.json'
        ;;
    esac
    return 0
}
complete -F _camgen camgen
