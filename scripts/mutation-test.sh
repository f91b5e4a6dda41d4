#!/usr/bin/env bash
# Mutation run: does the test suite catch plausible physics bugs?
#
# What it does. Copies the source tree to a private folder (never touching the repository's own
# files), builds it there (Release, Ninja, no benchmarks) and runs the test suite once unmutated
# (the baseline). Then, one at a time, it applies a deliberate bug (a "mutant"), rebuilds in the
# same build folder (so only what the edit touches recompiles), runs ctest (label `stress`
# excluded), and restores the file. It prints a table: each mutant and the tests that failed with
# it (caught; a test that already fails on the baseline does not count) or NOT CAUGHT.
#
# Where a mutant edits. The plugin's sources carry a marker comment `// mutation-site: NAME` on
# each line a mutant changes (or alone on the line above it); a mutant finds its markers and
# applies a regular-expression substitution to those lines only, so the sites survive code moving
# between files or functions. A mutant whose marker is missing, or whose substitution leaves a
# marked line unchanged, does not apply: the script stops (exit status 2) before building.
#
# The mutants (--list prints them with whether each applies to the working tree):
#   1 rope-weight      the rope material has no weight (SpanModel's gravity set to zero before its
#                      validation; the condensed axial modes read the same gravity)
#   2 linear-strain    the axial strain energy takes the engineering strain lambda - 1 instead of the
#                      Green strain (AxialLaw: energy EA (lambda - 1)^2 / 2, i.e. tension EA (lambda - 1),
#                      energy-consistent, for the dynamic and the condensed axial modes alike)
#   3 qv-forces        no quadratic-velocity forces in the spans (SpanModel's Q_v zeroed; the kinetic
#                      energy kept)
#   4 sheave-sense     turning and traction sheaves turn the wrong way in the material-coordinate
#                      relation s = s_ref + sense R theta (TurningSheaveNode: sense negated; drums unchanged)
#   5 mode-accel       no mode-acceleration correction (RopeModel::recoverInertialStrain's result
#                      marked invalid, so force queries use the uncorrected condensed strain)
#   6 arc-mass         the rope wrapped on a sheave's groove has no inertia (GrooveArc's mass matrix
#                      zeroed; its weight, kinetic energy and quadratic-velocity forces kept)
#   7 arc-qv-forces    the wrapped arc's quadratic-velocity forces zeroed (GrooveArc)
#   8 wrap-jacobian    the arc length l = R alpha has a zero row in the station map's Jacobian
#                      (WrapStationMap; its value and bias kept, a drum's s_0 row kept)
#   9 up-direction     the "up" a gripping groove measures its angle from is +x instead of +y without
#                      gravity (WrapStationMap::upDirection)
#  10 ring-speed       the stored rope's ring on a wrapped drum moves at the tangent point's material
#                      rate sdot instead of the drum's surface speed sdot - sigma R phidot (StoredRope)
#  11 capstan-exponent the capstan exponent mu alpha halved wherever the law is evaluated: the stick
#                      limit e^(mu alpha), the slip ratio and slip law, the friction 1 - e^(-mu alpha)
#                      of TractionSlip::RopeMomentum (TractionSheaveRun)
#  12 rhoa-v2          the rope's centripetal load rhoA v^2 dropped from the groove's normal load
#                      P - rhoA v^2, in the RopeMomentum slip law and its stick limit (TractionSheaveRun)
#  13 tight-side       RopeMomentum slip takes the slack side's tension as the tight one (TractionSheaveRun)
#  14 arc-length       the rope on a groove measured as R alpha / 2: a wrapped sheave's arc length
#                      and a gripping groove's (drum, turning sheave) R phi halved in the station map,
#                      consistently in its value, Jacobian and bias (WrapStationMap)
#  15 grip-stretch     a wrapped drum does not grip its rope: the rope leaves the groove at the groove's
#                      rate (1 / lambda -> 1 in RopeModel::applyGripRates; no creep, the same bias)
#  16 creep-weight     the grip's creep has no weight: the creep's mass held at the tangent point's
#                      height (its energy rate and its force on s) dropped (RopeModel::applyGripTerms)
#  17 bias-inertia     the RopeMomentum slip law and the stick friction drop the station map's bias
#                      inertia J^T M b (a gripping drum's stretch rate; TractionSheaveRun)
#
# How long it takes. On 2 cores shared with other work (Debian bookworm, g++ 12), under `nice`:
# about 9 min for the first build of a copy, 2.5-4 min per run of the suite (350 tests), under a
# minute to rebuild a mutant of a .cpp file and 7 min for the header mutant (linear-strain, run
# last: nearly everything includes it); 55 min in all for the baseline and mutants 1-13 once the
# copy is built (docs/testing.md). A second run reuses the copy and its build folder: only files
# that changed since are recopied and recompiled (after the header mutant's restore, that is nearly
# everything again: about 6 min).
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
#   --list               list the mutants, each with its files and whether it applies to the
#                        repository's working tree (no copy, no build), and exit
#   -h, --help           this text
# Exit status: 0 every mutant caught; 1 some mutant not caught; 2 bad usage, a mutant that does not
# apply (also with --list), or a setup failure (the copy or a mutant does not build).
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
# Each mutant is a list of sites: `site FILE NAME EDIT [TEXT]` finds, in FILE (relative to the
# tree's root), every line that carries the marker comment `// mutation-site: NAME`, and applies
# the Perl expression EDIT (a substitution, or several joined by `or`) to $_, the line's code: the
# marked line itself without its marker, or the line below a marker that stands alone. $ENV{TEXT}
# is TEXT, for a longer replacement. A site fails (the mutant does not apply: exit status 2) if
# FILE has no such marker or the edit leaves any marked line unchanged. Each changed line gets a
# /* MUTANT */ comment (the restore checks that none is left).
names=(rope-weight linear-strain qv-forces sheave-sense mode-accel arc-mass arc-qv-forces wrap-jacobian
    up-direction ring-speed capstan-exponent rhoa-v2 tight-side arc-length grip-stretch creep-weight bias-inertia)
descriptions=(
    "SpanModel gravity -> 0 (the rope material has no weight)"
    "AxialLaw: Green strain eps -> engineering strain lambda - 1 (energy and force)"
    "SpanModel Q_v -> 0 (quadratic-velocity forces; the kinetic energy kept)"
    "TurningSheave s = s_ref + sense R theta -> s_ref - sense R theta"
    "recoverInertialStrain's mode-acceleration correction marked invalid"
    "GrooveArc mass matrix -> 0 (the wrapped arc's inertia)"
    "GrooveArc quadratic-velocity forces -> 0"
    "WrapStationMap: the row of l = R alpha in the Jacobian -> 0 (bias kept)"
    "WrapStationMap::upDirection without gravity: +y -> +x"
    "StoredRope on a wrapped drum: ring speed sdot - sigma R phidot -> sdot"
    "capstan exponent mu alpha -> mu alpha / 2 (stick limit and slip laws)"
    "rhoA v^2 dropped from the capstan law and from the stick limit"
    "RopeMomentum slip: tight side swapped (sigma > 0 ? P_a : P_b -> P_b : P_a)"
    "WrapStationMap: the rope on a groove R alpha -> R alpha / 2 (arcs and gripped rope)"
    "wrapped drum's grip: sdot = v / lambda -> v (RopeModel::applyGripRates)"
    "the grip's creep weightless: its held weight's energy and force dropped (RopeModel)"
    "RopeMomentum slip and stick friction without the station map's bias inertia J^T M b"
)

mutant_1() {
    site plugin/element/src/SpanModel.cpp rope-weight 's/^(\s*)/$1gravity_.setZero(); /' || return 1
}

linearStrainHelpers='}  // namespace SimbodyReeving

#include <cmath>

namespace SimbodyReeving {

inline double reciprocal(double a) { return 1.0 / a; }  // MUTANT helper (Taylor numbers have their own)
// MUTANT: the engineering strain lambda - 1 = 2 eps / (1 + lambda) instead of the Green strain eps:
// energy density (lambda - 1)^2 / 2, its derivative with respect to eps (lambda - 1) / lambda.
template <class Scalar>
Scalar engineeringStrain(const Scalar& eps) {
    using std::sqrt;
    return (2.0 * eps) * reciprocal(Scalar(1.0) + sqrt(Scalar(1.0) + 2.0 * eps));
}
template <class Scalar>
Scalar linearStrainEnergy(const Scalar& eps) {
    const Scalar d = engineeringStrain(eps);
    return 0.5 * (d * d);
}
template <class Scalar>
Scalar linearStrainForce(const Scalar& eps) {
    using std::sqrt;
    return engineeringStrain(eps) * reciprocal(sqrt(Scalar(1.0) + 2.0 * eps));
}
'
mutant_2() {
    site plugin/element/include/SimbodyReeving/element/AxialLaw.h linear-strain '
        s/^struct AxialLaw \{/$ENV{TEXT}struct AxialLaw {/ or
        s/return eps;/return linearStrainForce(eps);/ or
        s/0\.5 \* \(eps \* eps\)/linearStrainEnergy(eps)/ or
        s/return 1\.0;/return 1.0 \/ ((1.0 + 2.0 * eps) * std::sqrt(1.0 + 2.0 * eps));/' "$linearStrainHelpers" || return 1
}

mutant_3() {
    site plugin/element/src/SpanModel.cpp qv-forces 's/;\s*$/; Qv.setZero();/' || return 1
}

mutant_4() {
    site plugin/simbody/src/nodes/TurningSheaveNode.cpp sheave-sense 's/= site\.spec\.sense \*/= -site.spec.sense */' || return 1
}

mutant_5() {
    site plugin/element/src/RopeModel.cpp mode-accel 's/inertialCorrectionValid = true/inertialCorrectionValid = false/' || return 1
}

mutant_6() {
    site plugin/element/src/GrooveArc.cpp arc-mass 's/massMatrix = rhoA \* R \*/massMatrix = 0.0 * rhoA * R */' || return 1
}

mutant_7() {
    site plugin/element/src/GrooveArc.cpp arc-qv-forces 's/velocityForces = (.*);/velocityForces = 0.0 * ($1);/' || return 1
}

mutant_8() {
    # l's row: R sigma phi_out from the span the arc starts, -R sigma phi_in from the one it ends
    # (a drum's row, s_0's, kept).
    site plugin/element/src/WrapStationMap.cpp wrap-jacobian '
        s/rowsOver\(6, arcScale\(j\), row\)/rowsOver(6, drum ? arcScale(j) : 0.0, row)/ or
        s/rowsOver\(7, -arcScale\(j \+ 1\), arcRow\(j \+ 1\)\)/rowsOver(7, 0.0, arcRow(j + 1))/' || return 1
}

mutant_9() {
    site plugin/element/src/WrapStationMap.cpp up-direction 's/Eigen::Vector3d\(0\.0, 1\.0, 0\.0\)/Eigen::Vector3d(1.0, 0.0, 0.0)/' ||
        return 1
}

mutant_10() {
    site plugin/element/src/StoredRope.cpp ring-speed 's/v = sdot - sigma \* R \* phidot;/v = sdot;/' || return 1
}

mutant_11() {
    site plugin/simbody/src/nodes/TractionSheaveRun.cpp capstan-exponent 's/\bfrictionCoefficient\b/(0.5 * frictionCoefficient)/g' ||
        return 1
}

mutant_12() {
    site plugin/simbody/src/nodes/TractionSheaveRun.cpp rhoa-v2 's/std::max\(tight - ([^,]*), 0\.0\)/std::max(tight - 0.0 * $1, 0.0)/' || return 1
}

mutant_13() {
    site plugin/simbody/src/nodes/TractionSheaveRun.cpp tight-side 's/sigma > 0 \? pa : pb/sigma > 0 ? pb : pa/' || return 1
}

mutant_14() {
    site plugin/element/src/WrapStationMap.cpp arc-length '
        s/return rope\.arc\(k\)\.radius\(\) \*/return 0.5 * rope.arc(k).radius() */ or
        s/= arc\.radius\(\) \* alpha;/= 0.5 * arc.radius() * alpha;/' || return 1
}

mutant_15() {
    site plugin/element/src/RopeModel.cpp grip-stretch 's/= 1\.0 \/ std::sqrt\(stretch2\);/= 1.0 + 0.0 * stretch2;/' || return 1
}

mutant_16() {
    site plugin/element/src/RopeModel.cpp creep-weight 's/if \(hasRing\)/if (false \&\& hasRing)/' || return 1
}

mutant_17() {
    site plugin/simbody/src/nodes/TractionSheaveRun.cpp bias-inertia 's/\? data\.nodeMassBias\[external\] : 0\.0/? 0.0 * data.nodeMassBias[external] : 0.0/' ||
        return 1
}

# The Perl half of `site`: ARGV = FILE WRITE; prints "markers changed unchanged-line-numbers".
sitePerl='
    my ($file, $write) = @ARGV;
    open(my $in, "<", $file) or die "cannot read $file\n";
    my $text = do { local $/; <$in> };
    close $in;
    my @lines = split /\n/, $text, -1;
    my $marker = qr{\s*//\s*mutation-site:\s*\Q$ENV{NAME}\E\s*$};
    my ($found, $changed, @unchanged) = (0, 0);
    for my $i (0 .. $#lines) {
        next unless $lines[$i] =~ $marker;
        ++$found;
        (my $code = $lines[$i]) =~ s/$marker//;
        my ($j, $suffix) = ($i, substr($lines[$i], length $code));
        if ($code !~ /\S/) { ($j, $suffix) = ($i + 1, ""); $code = $lines[$j] // ""; }
        local $_ = $code;
        eval $ENV{EDIT};
        die "the edit is not valid Perl: $@" if $@;
        if ($_ eq $code) { push @unchanged, $j + 1; next; }
        $lines[$j] = $_ . " /* MUTANT */" . $suffix;
        ++$changed;
    }
    print "$found $changed @unchanged\n";
    if ($write && $found > 0 && !@unchanged) {
        open(my $out, ">", $file) or die "cannot write $file\n";
        print $out join("\n", @lines);
        close $out;
    }
'
root=$repo         # the tree the sites are read from (the copy, once made)
applyEdits=0       # 1: write the edits (else only check that they apply)
siteFiles=()
site() {  # site FILE NAME EDIT [TEXT]
    local file=$root/$1 result found changed unchanged
    siteFiles+=("$1")
    [[ -f $file ]] || { echo "$1 does not exist" >&2; return 1; }
    if [[ $applyEdits == 1 ]]; then
        local saved
        saved=$work/saved/$(printf '%s' "$1" | tr / _)
        if [[ ! -f $saved ]]; then  # the original, before the mutant's first edit of this file
            cp -p "$file" "$saved"
            printf '%s\n' "$1" >> "$work/saved/list"
        fi
    fi
    result=$(NAME=$2 EDIT=$3 TEXT=${4-} perl -e "$sitePerl" "$file" "$applyEdits") || return 1
    read -r found changed unchanged <<< "$result"
    if [[ $found == 0 ]]; then
        echo "$1 has no marker 'mutation-site: $2'" >&2
        return 1
    fi
    if [[ -n $unchanged ]]; then
        echo "$1: the edit changes nothing on line(s) $unchanged (marker 'mutation-site: $2')" >&2
        return 1
    fi
}

# checkMutant <number>: does the mutant apply to $root? (Nothing written.) Sets checkFiles, the
# files it edits, and checkError, empty if it applies.
checkMutant() {
    local errFile
    errFile=$(mktemp)
    siteFiles=()
    applyEdits=0
    checkError=""
    if ! "mutant_$1" 2> "$errFile"; then
        checkError=$(paste -sd';' "$errFile" | sed 's/;/; /g')
        [[ -n $checkError ]] || checkError="the mutant failed"
    fi
    rm -f "$errFile"
    mapfile -t checkFiles < <(printf '%s\n' "${siteFiles[@]}" | awk 'NF && !seen[$0]++')
    [[ -z $checkError ]]
}

if [[ ${listOnly:-0} == 1 ]]; then
    status=0
    for i in "${!names[@]}"; do
        m=$((i + 1))
        if checkMutant "$m"; then state="applies"; else state="DOES NOT APPLY: $checkError"; status=2; fi
        printf '%2d %-17s %s (%s: %s)\n' "$m" "${names[i]}" "${descriptions[i]}" \
            "$(IFS=,; echo "${checkFiles[*]}" | sed 's/,/, /g')" "$state"
    done
    exit $status
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
srcReal=$(cd "$src" && pwd -P)/
[[ $srcReal != "$(cd "$repo" && pwd -P)/"* ]] || die "the work folder must not be inside the repository"
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

# Every selected mutant must apply to the copy before anything is built.
root=$src
for i in "${!names[@]}"; do
    isSelected $((i + 1)) || continue
    checkMutant $((i + 1)) || die "mutant $((i + 1)) (${names[i]}) does not apply: $checkError (see --list)"
done

# ---- helpers -----------------------------------------------------------------------------------
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
order=()
for i in "${!names[@]}"; do [[ ${names[i]} == linear-strain ]] || order+=($((i + 1))); done
order+=(2)
declare -A result=() detail=() times=()
notCaught=0
setupError=0
for m in "${order[@]}"; do
    isSelected "$m" || continue
    name=${names[m - 1]}
    mkdir -p "$work/saved"
    siteFiles=()
    applyEdits=1
    if ! "mutant_$m" 2> "$logs/edit-$m-$name.log"; then
        cat "$logs/edit-$m-$name.log" >&2
        restore
        result[$m]="EDIT FAILED"
        detail[$m]="the mutant does not apply (see --list)"
        setupError=1
        continue
    fi
    applyEdits=0
    t0=$(date +%s)
    echo "mutation-test: mutant $m ($name): building (log: $logs/build-$m-$name.log)"
    if ! configure_and_build "$logs/build-$m-$name.log"; then
        restore
        result[$m]="BUILD FAILED"
        detail[$m]="the mutant does not compile (see $logs/build-$m-$name.log): update the mutant"
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
    times[$m]="build $(hms $tb), tests $(hms $tt)"
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
    echo "mutation-test: mutant $m ($name): ${result[$m]} (${times[$m]})"
done

# ---- the table ---------------------------------------------------------------------------------
total=$(($(date +%s) - start))
echo
echo "Mutation run on the $what; ctest -LE stress${testsRegex:+ -R '$testsRegex'}${excludeRegex:+ -E '$excludeRegex'}"
[[ -n $baselineTests ]] && echo "baseline: $baselineTests (tests failing unmutated do not count as catching)"
printf '%-3s %-17s %-78s %s\n' "#" "mutant" "edit" "result"
for i in "${!names[@]}"; do
    m=$((i + 1))
    isSelected "$m" || continue
    [[ -n ${result[$m]+x} ]] || continue
    printf '%-3s %-17s %-78s %s\n' "$m" "${names[m - 1]}" "${descriptions[m - 1]}" \
        "${result[$m]}${times[$m]:+ (${times[$m]})}"
    [[ -n ${detail[$m]} ]] && printf '%s\n' "${detail[$m]}" | tr ';' '\n' | sed 's/^ *//; s/^/        /'
done
echo "total: $(hms $total) ($jobs jobs; logs and the caught tests of each mutant in $logs)"
if [[ $setupError == 1 ]]; then exit 2; fi
if [[ $notCaught == 1 ]]; then exit 1; fi
exit 0
