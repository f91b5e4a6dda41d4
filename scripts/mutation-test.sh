#!/usr/bin/env bash
# Mutation run: does the test suite catch plausible physics bugs?
#
# What it does. Copies the source tree to a private folder (never touching the repository's own
# files), builds it there (Release, Ninja, no benchmarks) and runs the test suite once unmutated
# (the baseline). Then, one at a time, it applies a deliberate bug (a "mutant": a small, exact
# source edit whose match count is verified before it is applied), rebuilds in the same build
# folder (so only what the edit touches recompiles), runs ctest (label `stress` excluded), and
# restores the file. It prints a table: each mutant and the tests that failed with it (caught; a
# test that already fails on the baseline does not count) or NOT CAUGHT.
#
# The mutants:
#   1 rope-weight     the rope material has no weight (SpanModel's gravity set to zero after its
#                     validation; the condensed axial modes read the same gravity)
#   2 linear-strain   the axial strain energy takes the engineering strain lambda - 1 instead of the
#                     Green strain (AxialLaw: energy EA (lambda - 1)^2 / 2, i.e. tension EA (lambda - 1),
#                     energy-consistent, for the dynamic and the condensed axial modes alike)
#   3 qv-forces       no quadratic-velocity forces (SpanModel's Q_v zeroed; the kinetic energy kept)
#   4 sheave-sense    turning and traction sheaves turn the wrong way in the material-coordinate
#                     relation s = s_ref + sense R theta (the sign of sense flipped; drums unchanged)
#   5 mode-accel      no mode-acceleration correction (RopeModel::recoverInertialStrain's result
#                     marked invalid, so force queries use the uncorrected condensed strain)
#   6 arc-mass        slot: zero the arc mass of wrapped sheaves; not applicable until wrapped sheaves
#                     exist (listed, never counted as caught)
#
# How long it takes. On 2 cores shared with other work (Debian bookworm, g++ 12), under `nice`:
# about 18 min for the first build of a copy, 3-7 min per run of the suite, 1-2 min to rebuild a
# mutant of a .cpp file and 12 min for the header mutant (linear-strain, run last: nearly everything
# includes it); 65 min in all for the baseline and the five mutants (docs/testing.md). A second run
# reuses the copy and its build folder: only files that changed since are recopied and recompiled
# (after the header mutant's restore, that is nearly everything again).
#
# Usage: scripts/mutation-test.sh [options]
#   --working-tree       copy the working tree (tracked files as they are on disk, plus untracked
#                        files that are not ignored), e.g. uncommitted tests; default: HEAD only
#   --tests REGEX        run only the tests matching REGEX (ctest -R)
#   --exclude REGEX      skip the tests matching REGEX (ctest -E)
#   --mutants LIST       run only these mutants (comma-separated numbers or names, e.g. 1,mode-accel)
#   --no-baseline        skip the unmutated run (every failing test then counts as catching)
#   --timeout SECONDS    per-test timeout (default 900): a mutant that makes a test hang is caught
#                        by the timeout, reported as such
#   --jobs N             build and test parallelism (default: the number of cores)
#   --work-dir DIR       the private copy and its build (default ${TMPDIR:-/tmp}/simbodyreeving-mutation)
#   --list               list the mutants and exit
#   -h, --help           this text
# Exit status: 0 every applicable mutant caught; 1 some mutant not caught; 2 bad usage, or a setup
# failure (the copy does not build, an edit no longer matches the source: update the mutant).
# The log of every build and test run is kept in the work folder (logs/).
set -euo pipefail

repo=$(cd "$(dirname "$0")/.." && pwd)
workingTree=0
testsRegex=""
excludeRegex=""
selected=""
baseline=1
timeout=900
jobs=$(nproc)
work=${TMPDIR:-/tmp}/simbodyreeving-mutation

usage() { sed -n '2,/^set -euo/p' "$0" | sed '$d' | sed 's/^# \{0,1\}//'; }
die() { echo "mutation-test: $*" >&2; exit 2; }

while [[ $# -gt 0 ]]; do
    case $1 in
        --working-tree) workingTree=1 ;;
        --tests) testsRegex=${2:?--tests needs a regex}; shift ;;
        --exclude) excludeRegex=${2:?--exclude needs a regex}; shift ;;
        --mutants) selected=${2:?--mutants needs a list}; shift ;;
        --no-baseline) baseline=0 ;;
        --timeout) timeout=${2:?--timeout needs seconds}; shift ;;
        --jobs) jobs=${2:?--jobs needs a number}; shift ;;
        --work-dir) work=${2:?--work-dir needs a folder}; shift ;;
        --list) listOnly=1 ;;
        -h|--help) usage; exit 0 ;;
        *) die "unknown option $1 (see --help)" ;;
    esac
    shift
done
[[ $timeout =~ ^[0-9]+$ && $jobs =~ ^[1-9][0-9]*$ ]] || die "--timeout and --jobs take positive integers"

# ---- the mutants -------------------------------------------------------------------------------
# Each is a list of exact edits: edit FILE OLD NEW COUNT replaces the COUNT occurrences of the
# literal text OLD (relative to the copy's root) by NEW, and fails if OLD occurs any other number
# of times (the source moved on: update the mutant).
names=(rope-weight linear-strain qv-forces sheave-sense mode-accel arc-mass)
descriptions=(
    "drop the rope weight (SpanModel gravity = 0)"
    "linear instead of Green strain in the axial strain energy (AxialLaw)"
    "drop the quadratic-velocity forces (SpanModel Q_v = 0)"
    "flip the turning/traction sheave sense in s = s_ref + sense R theta"
    "drop the mode-acceleration correction (recoverInertialStrain)"
    "zero the arc mass of wrapped sheaves"
)
applicable=(1 1 1 1 1 0)
notApplicableReason="not applicable until wrapped sheaves exist"

mutant_1() {
    edit plugin/element/src/SpanModel.cpp \
'        throwInvalid("SpanModel", "gravity [m/s^2]", v.str(), "must be finite");
    }
' \
'        throwInvalid("SpanModel", "gravity [m/s^2]", v.str(), "must be finite");
    }
    gravity_.setZero();  // MUTANT: the rope material has no weight
' 1 || return 1
}

mutant_2() {
    local f=plugin/element/include/SimbodyReeving/element/AxialLaw.h
    edit $f '#include "SimbodyReeving/element/RopeProperties.h"
' '#include "SimbodyReeving/element/RopeProperties.h"

#include <cmath>
' 1 || return 1
    edit $f 'struct AxialLaw {
' 'inline double reciprocal(double a) { return 1.0 / a; }  // MUTANT helper (Taylor numbers have their own)

struct AxialLaw {
    // MUTANT: the engineering strain lambda - 1 = 2 eps / (1 + lambda) instead of the Green strain eps:
    // energy density (lambda - 1)^2 / 2, its derivative with respect to eps (lambda - 1) / lambda.
    template <class Scalar>
    static Scalar engineeringStrain(const Scalar& eps) {
        using std::sqrt;
        return (2.0 * eps) * reciprocal(Scalar(1.0) + sqrt(Scalar(1.0) + 2.0 * eps));
    }
    template <class Scalar>
    static Scalar linearStrainEnergy(const Scalar& eps) {
        const Scalar d = engineeringStrain(eps);
        return 0.5 * (d * d);
    }
    template <class Scalar>
    static Scalar linearStrainForce(const Scalar& eps) {
        using std::sqrt;
        return engineeringStrain(eps) * reciprocal(sqrt(Scalar(1.0) + 2.0 * eps));
    }
' 1 || return 1
    edit $f '        if (!tensionOnly || primal >= transition) return eps;
' '        if (!tensionOnly || primal >= transition) return linearStrainForce(eps);
' 1 || return 1
    edit $f '        if (!tensionOnly) return 0.5 * (eps * eps);
' '        if (!tensionOnly) return linearStrainEnergy(eps);
' 1 || return 1
    edit $f '        if (primal >= transition) return 0.5 * (eps * eps) - Scalar(0.1 * transition * transition);
' '        if (primal >= transition) return linearStrainEnergy(eps) - Scalar(0.1 * transition * transition);
' 1 || return 1
    edit $f '        if (!tensionOnly || eps >= transition) return 1.0;
' '        if (!tensionOnly || eps >= transition) return 1.0 / ((1.0 + 2.0 * eps) * std::sqrt(1.0 + 2.0 * eps));
' 1 || return 1
}

mutant_3() {
    edit plugin/element/src/SpanModel.cpp \
'    d.kineticEnergy = 0.5 * rhoA * l * sumV2;
' \
'    d.kineticEnergy = 0.5 * rhoA * l * sumV2;
    Qv.setZero();  // MUTANT: no quadratic-velocity forces
' 1 || return 1
}

mutant_4() {
    edit plugin/simbody/src/ReevingSubsystem.cpp \
'                    d.sRef = n.materialCoordinateAtZeroAngle;
                    d.dsdTheta = n.sense * n.radius;' \
'                    d.sRef = n.materialCoordinateAtZeroAngle;
                    d.dsdTheta = -n.sense * n.radius;  // MUTANT: the sheave turns the wrong way' 1 || return 1
}

mutant_5() {
    edit plugin/element/src/RopeModel.cpp \
'    data.inertialCorrectionValid = true;' \
'    data.inertialCorrectionValid = false;  // MUTANT: no mode-acceleration correction' 1 || return 1
}

mutant_6() {
    # Slot: once wrapped sheaves with a rope arc of their own exist, zero that arc's mass here (an
    # `edit` of the arc's mass term) and set applicable[5]=1 above.
    return 1
}

if [[ ${listOnly:-0} == 1 ]]; then
    for i in "${!names[@]}"; do
        printf '%d %-14s %s%s\n' $((i + 1)) "${names[i]}" "${descriptions[i]}" \
            "$([[ ${applicable[i]} == 1 ]] || echo " ($notApplicableReason)")"
    done
    exit 0
fi

isSelected() {  # isSelected <number>
    [[ -z $selected ]] && return 0
    local item
    for item in ${selected//,/ }; do
        [[ $item == "$1" || $item == "${names[$1 - 1]}" ]] && return 0
    done
    return 1
}
if [[ -n $selected ]]; then
    for item in ${selected//,/ }; do
        ok=0
        for i in "${!names[@]}"; do [[ $item == $((i + 1)) || $item == "${names[i]}" ]] && ok=1; done
        [[ $ok == 1 ]] || die "unknown mutant '$item' (see --list)"
    done
fi

# ---- the private copy --------------------------------------------------------------------------
src=$work/src
build=$work/build
logs=$work/logs
mkdir -p "$src" "$logs"
[[ $(cd "$src" && pwd -P) != "$(cd "$repo" && pwd -P)"* ]] || die "the work folder must not be inside the repository"
start=$(date +%s)

stage=$work/stage
rm -rf "$stage"
mkdir -p "$stage"
if [[ $workingTree == 1 ]]; then
    git -C "$repo" ls-files -z -co --exclude-standard |
        (cd "$repo" && while IFS= read -r -d '' f; do [[ -f $f ]] && printf '%s\0' "$f"; done) |
        tar -C "$repo" --null -T - -cf - | tar -x -C "$stage"
    what="working tree of $(git -C "$repo" rev-parse --short HEAD) (with uncommitted changes)"
else
    git -C "$repo" archive HEAD | tar -x -C "$stage"
    what="HEAD $(git -C "$repo" rev-parse --short HEAD)"
fi
# Sync into the copy, file by file, so unchanged files keep their times and do not recompile.
(cd "$stage" && find . -type f -print0) | while IFS= read -r -d '' f; do
    if ! cmp -s "$stage/$f" "$src/$f"; then
        mkdir -p "$(dirname "$src/$f")"
        cp "$stage/$f" "$src/$f"
    fi
done
(cd "$src" && find . -type f -print0) | while IFS= read -r -d '' f; do
    [[ -e $stage/$f ]] || rm -f "$src/$f"
done
rm -rf "$stage"
echo "mutation-test: $what copied to $src"

# ---- helpers -----------------------------------------------------------------------------------
edit() {  # edit FILE OLD NEW COUNT (FILE relative to the copy)
    local file=$src/$1
    local n
    [[ -f $file ]] || { echo "edit: $1 does not exist" >&2; return 1; }
    n=$(OLD=$2 perl -0777 -ne 'my ($n, $p) = (0, 0);
            while (($p = index($_, $ENV{OLD}, $p)) >= 0) { ++$n; $p += length $ENV{OLD}; } print $n' "$file")
    if [[ $n != "$4" ]]; then
        echo "edit: the text to replace occurs $n times in $1 (expected $4):" >&2
        printf '%s\n' "$2" | sed 's/^/    | /' >&2
        return 1
    fi
    local saved
    saved=$work/saved/$(printf '%s' "$1" | tr / _)
    if [[ ! -f $saved ]]; then  # the original, before the mutant's first edit of this file
        cp -p "$file" "$saved"
        printf '%s\n' "$1" >> "$work/saved/list"
    fi
    cp -p "$file" "$saved.before"
    OLD=$2 NEW=$3 perl -0777 -pi -e 's/\Q$ENV{OLD}\E/$ENV{NEW}/g' "$file"
    if cmp -s "$file" "$saved.before"; then echo "edit: $1 unchanged" >&2; return 1; fi
    rm -f "$saved.before"
    return 0
}
restore() {  # puts back every file an edit changed (a new time stamp: the next build recompiles it)
    [[ -f $work/saved/list ]] || return 0
    local f
    while IFS= read -r f; do
        cat "$work/saved/$(printf '%s' "$f" | tr / _)" > "$src/$f"
        if grep -q "MUTANT" "$src/$f"; then
            echo "mutation-test: $f still holds a mutant after its restore: delete $work to start afresh" >&2
            exit 2
        fi
    done < <(sort -u "$work/saved/list")
    rm -rf "$work/saved"
}
trap restore EXIT
trap 'exit 130' INT TERM

configure_and_build() {  # configure_and_build <log>
    if [[ ! -f $build/CMakeCache.txt ]]; then
        nice -n 10 cmake -S "$src" -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=Release \
            -DSIMBODYREEVING_BUILD_BENCHMARKS=OFF > "$1" 2>&1 || return 1
    fi
    nice -n 10 cmake --build "$build" -j"$jobs" >> "$1" 2>&1
}

failedTests=()
run_tests() {  # run_tests <log>: sets failedTests ("name (reason)")
    local args=(--test-dir "$build" -j"$jobs" -LE stress --timeout "$timeout" --output-on-failure)
    [[ -n $testsRegex ]] && args+=(-R "$testsRegex")
    [[ -n $excludeRegex ]] && args+=(-E "$excludeRegex")
    nice -n 10 ctest "${args[@]}" > "$1" 2>&1 || true
    grep -q "tests passed" "$1" || { echo "ctest did not run (see $1)" >&2; return 1; }
    mapfile -t failedTests < <(sed -n '/The following tests FAILED:/,$p' "$1" |
        sed -n 's/^[[:space:]]*[0-9]\{1,\} - \(.*\) (\(.*\))$/\1 (\2)/p')
}
hms() { printf '%d min %02d s' $(($1 / 60)) $(($1 % 60)); }

# ---- baseline ----------------------------------------------------------------------------------
rm -rf "$work/saved"
mkdir -p "$work/saved"
t0=$(date +%s)
echo "mutation-test: building the unmutated copy (log: $logs/build-baseline.log)"
configure_and_build "$logs/build-baseline.log" ||
    { tail -30 "$logs/build-baseline.log" >&2; die "the unmutated copy does not build (see $logs/build-baseline.log)"; }
baselineBuild=$(($(date +%s) - t0))
declare -A baselineFailed=()
baselineTests=""
if [[ $baseline == 1 ]]; then
    t0=$(date +%s)
    echo "mutation-test: running the unmutated suite (log: $logs/test-baseline.log)"
    run_tests "$logs/test-baseline.log" || die "the baseline test run failed to start"
    for t in "${failedTests[@]}"; do baselineFailed["${t% (*}"]=1; done
    baselineTests=$(grep -o '[0-9]*% tests passed, [0-9]* tests failed out of [0-9]*' "$logs/test-baseline.log" | tail -1)
    echo "mutation-test: baseline: $baselineTests, $(hms $(($(date +%s) - t0))) (build $(hms $baselineBuild))"
    for t in "${failedTests[@]}"; do echo "    fails unmutated (not counted): $t"; done
fi

# ---- mutants -----------------------------------------------------------------------------------
# Order of the runs: the header mutant last (it recompiles almost everything, and so does its restore).
order=(1 3 4 5 2 6)
declare -A result=() detail=()
notCaught=0
setupError=0
for m in "${order[@]}"; do
    isSelected "$m" || continue
    name=${names[m - 1]}
    if [[ ${applicable[m - 1]} != 1 ]]; then
        result[$m]="n/a"
        detail[$m]=$notApplicableReason
        continue
    fi
    mkdir -p "$work/saved"
    if ! "mutant_$m" 2> "$logs/edit-$m-$name.log"; then
        cat "$logs/edit-$m-$name.log" >&2
        restore
        result[$m]="EDIT FAILED"
        detail[$m]="the edit no longer matches the source (update the mutant)"
        setupError=1
        continue
    fi
    t0=$(date +%s)
    echo "mutation-test: mutant $m ($name): building (log: $logs/build-$m-$name.log)"
    if ! configure_and_build "$logs/build-$m-$name.log"; then
        restore
        result[$m]="BUILD FAILED"
        detail[$m]="the mutant does not compile (see $logs/build-$m-$name.log; update the mutant)"
        setupError=1
        continue
    fi
    tb=$(($(date +%s) - t0))
    echo "mutation-test: mutant $m ($name): running the suite (log: $logs/test-$m-$name.log)"
    if ! run_tests "$logs/test-$m-$name.log"; then
        restore
        result[$m]="TESTS DID NOT RUN"
        detail[$m]="see $logs/test-$m-$name.log"
        setupError=1
        continue
    fi
    restore
    caught=()
    for t in "${failedTests[@]}"; do
        [[ -n ${baselineFailed["${t% (*}"]+x} ]] || caught+=("$t")
    done
    tt=$(($(date +%s) - t0 - tb))
    if [[ ${#caught[@]} -gt 0 ]]; then
        result[$m]="caught by ${#caught[@]}"
        detail[$m]=$(printf '%s; ' "${caught[@]}")
        detail[$m]=${detail[$m]%; }
    else
        result[$m]="NOT CAUGHT"
        detail[$m]=""
        notCaught=1
    fi
    printf '%s\n' "${caught[@]}" > "$logs/caught-$m-$name.txt"
    echo "mutation-test: mutant $m ($name): ${result[$m]} (build $(hms $tb), tests $(hms $tt))"
done

# ---- the table ---------------------------------------------------------------------------------
total=$(($(date +%s) - start))
echo
echo "Mutation run on the $what; ctest -LE stress${testsRegex:+ -R '$testsRegex'}${excludeRegex:+ -E '$excludeRegex'}"
[[ -n $baselineTests ]] && echo "baseline: $baselineTests (tests failing unmutated do not count as catching)"
printf '%-3s %-14s %-70s %s\n' "#" "mutant" "edit" "result"
for m in 1 2 3 4 5 6; do
    isSelected "$m" || continue
    [[ -n ${result[$m]+x} ]] || continue
    printf '%-3s %-14s %-70s %s\n' "$m" "${names[m - 1]}" "${descriptions[m - 1]}" "${result[$m]}"
    [[ -n ${detail[$m]} ]] && printf '%s\n' "${detail[$m]}" | tr ';' '\n' | sed 's/^ *//; s/^/        /'
done
echo "total: $(hms $total) ($jobs jobs; logs and the caught tests of each mutant in $logs)"
if [[ $setupError == 1 ]]; then exit 2; fi
if [[ $notCaught == 1 ]]; then exit 1; fi
exit 0
