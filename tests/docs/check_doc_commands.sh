#!/usr/bin/env bash
# Every command the documents quote still runs with the options it shows.
#
# Reads docs/*.md and bench/RESULTS.md and collects the commands: the lines of ```sh / ```bash /
# ```shell / ```console / plain ``` blocks (continuation lines joined), the commands named by the
# tables' `<!-- BEGIN generated: COMMAND -->` markers (scripts/regenerate-docs.sh), and inline code
# spans that start with a project program. Each command is split into its pipeline / list parts
# (&&, ||, |, ;); in each part the first project program is checked, wrappers before it
# (valgrind, taskset, mpirun, ...) and other tools skipped:
#   build/examples/*, build/tests/**   exists in BUILD_DIR; each --option shown appears in its
#                                      `--help` output;
#   build/bench/*                      exists in BUILD_DIR; each --option shown appears in the binary
#                                      (its option parser's literal), Google Benchmark's
#                                      --benchmark_* options in the program's `--help` output;
#   scripts/*.sh, bench/**.sh          exists and is executable; each --option shown appears in the
#                                      script's text, each VAR=value before it as $VAR or ${VAR.
# Positional arguments are not checked. Nothing but --help runs.
#
# usage: check_doc_commands.sh SOURCE_DIR BUILD_DIR
# Exit status: 0 every command checked; 1 a program is missing or an option unknown (each named).
set -uo pipefail
src=${1:?usage: check_doc_commands.sh SOURCE_DIR BUILD_DIR}
build=${2:?usage: check_doc_commands.sh SOURCE_DIR BUILD_DIR}
cd "$src" || exit 1
docs=(docs/*.md bench/RESULTS.md)
prog_re='^(\./)?(build/(examples|bench|tests)/[A-Za-z0-9_./-]*[A-Za-z0-9_]|scripts/[A-Za-z0-9_./-]+\.sh|bench/[A-Za-z0-9_./-]+\.sh)$'
failures=0
checked=0
declare -A helpCache

fail() { echo "FAIL $1: $2" >&2; failures=$((failures + 1)); }

# The commands of one document, one per line, prefixed with "FILE:LINE: ".
extract() {
    awk -v file="$1" '
        function flush() { if (cmd != "") print file ":" start ": " cmd; cmd = "" }
        /^[ \t]*```/ {
            if (!inBlock) { lang = $0; sub(/^[ \t]*```/, "", lang); inBlock = 1
                            take = (lang == "" || lang == "sh" || lang == "bash" || lang == "shell" || lang == "console") }
            else { flush(); inBlock = 0 }
            next
        }
        inBlock && take {
            line = $0; sub(/^[ \t]*\$ /, "", line)
            if (cmd == "") start = NR
            cont = (line ~ /\\[ \t]*$/); sub(/\\[ \t]*$/, "", line)
            cmd = cmd " " line
            if (!cont) flush()
            next
        }
        /^<!-- BEGIN generated( --all)?: / {
            c = $0; sub(/^<!-- BEGIN generated( --all)?: /, "", c); sub(/ -->[ \t]*$/, "", c)
            print file ":" NR ": " c; next
        }
        !inBlock {
            rest = $0
            while (match(rest, /`[^`]+`/)) {
                span = substr(rest, RSTART + 1, RLENGTH - 2); rest = substr(rest, RSTART + RLENGTH)
                if (span ~ /^(\.\/)?(build\/(examples|bench|tests)\/|scripts\/|bench\/)[^ ]*[A-Za-z0-9_]( |$)/) print file ":" NR ": " span
            }
        }' "$1"
}

# Shell words of a command (quotes honoured, not expanded), one per line; comments dropped.
words() {
    local s=$1 out= q= c i
    for ((i = 0; i < ${#s}; i++)); do
        c=${s:i:1}
        if [[ -n $q ]]; then
            [[ $c == "$q" ]] && q= || out+=$c
        elif [[ $c == "'" || $c == '"' ]]; then
            q=$c
        elif [[ $c == ' ' || $c == $'\t' ]]; then
            [[ -n $out ]] && printf '%s\n' "$out"; out=
        elif [[ $c == '#' && -z $out ]]; then
            break
        else
            out+=$c
        fi
    done
    [[ -n $out ]] && printf '%s\n' "$out"
}

help_of() {  # the --help text of a binary, cached
    if [[ -z ${helpCache[$1]+x} ]]; then
        helpCache[$1]=$(timeout 10 "$1" --help 2>&1 </dev/null)
    fi
    printf '%s' "${helpCache[$1]}"
}

has_word() {  # has_word TEXT OPTION: OPTION appears in TEXT, not as part of a longer option
    grep -qE -- "(^|[^A-Za-z0-9_-])${2}([^A-Za-z0-9_-]|$)" <<<"$1"
}

check_part() {  # check_part WHERE WORD...
    local where=$1; shift
    local env=() prog= opts=() w
    for w in "$@"; do
        if [[ -z $prog ]]; then
            if [[ $w =~ ^[A-Z_][A-Z0-9_]*= ]]; then env+=("${w%%=*}"); continue; fi
            [[ $w =~ $prog_re ]] && prog=${w#./}
            continue
        fi
        w=${w#[}; w=${w%]}
        [[ $w =~ ^--[A-Za-z0-9][A-Za-z0-9_-]*(=.*)?$ ]] && opts+=("${w%%=*}")
    done
    [[ -n $prog ]] || return 0
    checked=$((checked + 1))
    local o
    case $prog in
        build/*)
            local bin=$build/${prog#build/}
            [[ -x $bin ]] || { fail "$where" "$prog: not built ($bin)"; return; }
            for o in "${opts[@]}"; do
                if [[ $prog == build/bench/* ]]; then
                    grep -aqF -- "$o" "$bin" && continue
                    [[ $o == --benchmark_* ]] && has_word "$(help_of "$bin")" "$o" && continue
                else
                    has_word "$(help_of "$bin")" "$o" && continue
                fi
                fail "$where" "$prog has no option $o"
            done
            ;;
        *)
            [[ -x $prog ]] || { fail "$where" "$prog: no such executable script"; return; }
            for o in "${opts[@]}"; do
                grep -qF -- "$o" "$prog" || fail "$where" "$prog has no option $o"
            done
            for o in "${env[@]}"; do
                grep -qE -- "\\\$\\{?$o\\b" "$prog" || fail "$where" "$prog does not read $o"
            done
            ;;
    esac
}

for doc in "${docs[@]}"; do
    [[ -f $doc ]] || { fail "$doc" "missing"; continue; }
    while IFS= read -r line; do
        where=${line%%: *}
        cmd=${line#*: }
        part=()
        while IFS= read -r w; do
            case $w in
                '&&' | '||' | '|' | ';') check_part "$where" "${part[@]}"; part=() ;;
                *) part+=("$w") ;;
            esac
        done < <(words "$cmd")
        ((${#part[@]})) && check_part "$where" "${part[@]}"
    done < <(extract "$doc")
done

echo "check_doc_commands: $checked program invocations checked in ${docs[*]}, $failures failure(s)"
((failures == 0))
