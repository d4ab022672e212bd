#!/usr/bin/env bash
# The test suite: installs missing system packages, then runs the tests on the Vulkan device
# (on a machine without a GPU: Mesa's lavapipe) with validation and synchronization validation.
#
#   scripts/test.sh            the default tier: each feature's checks (7 to 11 minutes on a
#                              fresh 2-core machine once built, 3 to 4 more to build)
#   scripts/test.sh --all      the default tier, then the exhaustive one: the tests `#[ignore]`d
#                              as repeating a behaviour at a larger size or over more cases (CI)
#   scripts/test.sh FILTER     only the integration tests whose names contain FILTER
#                              (`scripts/test.sh self_contact::`)
#
# The unit tests run as `cargo test` runs them; the integration tests (tests/suite/) a file
# (module) a process, its tests one after another sharing one GPU context, as many processes
# at once as there are cores (the validation layer serialises the GPU work of threads of one
# process). Sharing the context shares its pipelines: lavapipe compiles each pipeline variant
# once a process, and compiling was most of a test's time. The first test of a process that
# fails (or dies) fails; those after it that do not pass run again each in a process of its
# own, and that run's result counts (a test that panics leaves its GPU objects behind, which
# would fail the next one's check); a process that ends in error after all its tests passed
# fails as its file. Options starting with `-` go to `cargo test --no-run`. Prints each
# test's result, each file's time, the time of the build and of each tier, and ends with one
# line of totals.
set -euo pipefail
cd "$(dirname "$0")/.."
all=0
cargo_args=()
filters=()
for a in "$@"; do
    case "$a" in
        --all) all=1 ;;
        -*) cargo_args+=("$a") ;;
        *) filters+=("$a") ;;
    esac
done
scripts/deps.sh test
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
seconds() { echo $(( $(date +%s) - $1 )); }

start=$(date +%s)
cargo test --locked --no-run --message-format=json-render-diagnostics "${cargo_args[@]}" > "$work/build.json"
times="build $(seconds "$start") s"
# (the test harnesses: artifacts of the test profile, not the msdsim binary the tests run)
executables=$(grep -E '"profile":\{[^}]*"test":true' "$work/build.json" | grep -o '"executable":"[^"]*"' \
    | sed 's/"executable":"\(.*\)"/\1/' | sort -u)
suite=$(grep '/suite-[0-9a-f]*$' <<< "$executables" || true)
[ -n "$suite" ] || { echo "test.sh: cargo built no tests/suite binary" >&2; exit 1; }

passed=0
failed=0
failures=()
# Unit tests (src/), all in their own binaries' threads: quick, and most need no GPU.
if [ "${#filters[@]}" = 0 ]; then
    start=$(date +%s)
    for exe in $(grep -v '/suite-[0-9a-f]*$' <<< "$executables"); do
        if "$exe" > "$work/unit.log" 2>&1; then :; else failures+=("unit tests of $exe"); cat "$work/unit.log"; fi
        read -r p f < <(awk '/^test result:/ { for (i = 1; i <= NF; i++) { if ($(i+1) ~ /^passed/) p += $i; if ($(i+1) ~ /^failed/) f += $i } } END { print p + 0, f + 0 }' "$work/unit.log")
        passed=$((passed + p))
        failed=$((failed + f))
    done
    times="$times, unit tests $(seconds "$start") s"
fi

# Where the output of integration test $1 is kept.
log_of() { echo "$work/$(printf '%s' "$1" | tr -c 'A-Za-z0-9_.-' '_').log"; }
# One integration test: its output kept, a line with its result and time.
run_one() {
    local name=$1 log
    log=$(log_of "$name")
    local t0=$SECONDS
    if "$suite" --exact "$name" --include-ignored --test-threads 1 > "$log" 2>&1; then
        printf 'PASS %4ds %s\n' $((SECONDS - t0)) "$name"
    else
        printf 'FAIL %4ds %s\n' $((SECONDS - t0)) "$name"
    fi
}
# The integration tests named in file $1 (one file's, of one tier) in one process sharing a
# context (`MSDSIM_TEST_SHARED_CONTEXT`, tests/suite/common). The first that did not pass
# there (failed, or was running when the process died) fails with the process's output; those
# after it that did not pass run alone (run_one).
run_file() {
    local file=$1 base log t0=$SECONDS name first status=0 count
    base=$(basename "$file")
    count=$(wc -l < "$file")
    log=$(log_of "$base")
    xargs -a "$file" -d '\n' env MSDSIM_TEST_SHARED_CONTEXT=1 "$suite" --exact --include-ignored \
        --test-threads 1 > "$log" 2>&1 < /dev/null || status=$?
    first=$(awk '/^test [^ ]+ \.\.\. / && $NF != "ok" { print $2; exit }' "$log")
    while read -r name; do
        if grep -qxF "test $name ... ok" "$log"; then
            printf 'PASS       %s\n' "$name"
        elif [ "$name" = "$first" ]; then
            cp "$log" "$(log_of "$name")"
            printf 'FAIL       %s\n' "$name"
        else
            run_one "$name" < /dev/null
        fi
    done < "$file"
    if [ "$status" != 0 ] && [ -z "$first" ] && [ "$(grep -c ' \.\.\. ok$' "$log")" = "$count" ]; then
        printf 'FAIL       %s\n' "$base"
    fi
    printf '     %4ds %s (%d tests)\n' $((SECONDS - t0)) "$base" "$count"
}
export -f log_of run_one run_file
export suite work
# The validation layer reports a message at most 10 times an instance by default: in a process
# that runs many tests on one instance, a later test's repeat of a message would go unreported.
export VK_LAYER_DUPLICATE_MESSAGE_LIMIT=1000000000

# The integration tests of a tier (`--ignored`: the exhaustive one), listed by the binary.
run_tier() {
    local tier=$1 listed
    listed=$("$suite" --list --format terse ${filters[@]+"${filters[@]}"} $([ "$tier" = exhaustive ] && echo --ignored) 2>/dev/null | sed -n 's/: test$//p')
    if [ "$tier" = default ]; then
        local ignored
        ignored=$("$suite" --list --format terse --ignored ${filters[@]+"${filters[@]}"} 2>/dev/null | sed -n 's/: test$//p')
        listed=$(comm -23 <(sort <<< "$listed") <(sort <<< "$ignored"))
    fi
    [ -n "$listed" ] || return 0
    local start
    start=$(date +%s)
    # (a file of names for each test file; the longest to run first, then by their tests'
    # count, so that no long one starts last)
    local dir="$work/$tier.files" longest="gpu_vs_cpu self_contact cli mesh_cloth"
    mkdir -p "$dir"
    while read -r name; do echo "$name" >> "$dir/${name%%::*}"; done <<< "$listed"
    {
        for m in $longest; do [ -f "$dir/$m" ] && echo "$dir/$m"; done
        for f in "$dir"/*; do
            grep -qw "$(basename "$f")" <<< "$longest" || echo "$(wc -l < "$f") $f"
        done | sort -rn | cut -d' ' -f2-
    } | xargs -P "$(nproc)" -I{} bash -c 'run_file "$1"' _ {} | tee "$work/$tier.results"
    times="$times, $tier tier $(seconds "$start") s"
    passed=$((passed + $(grep -c '^PASS' "$work/$tier.results" || true)))
    while read -r name; do
        failed=$((failed + 1))
        failures+=("$name")
        echo "---- $name ----"
        cat "$(log_of "$name")"
    done < <(sed -n 's/^FAIL *\([0-9]*s\)\? *//p' "$work/$tier.results")
}
run_tier default
if [ "$all" = 1 ]; then
    run_tier exhaustive
fi
[ "${#failures[@]}" = 0 ] || printf 'failed: %s\n' "${failures[@]}"
echo "time: $times"
echo "$passed passed, $failed failed"
[ "$failed" = 0 ] && [ "${#failures[@]}" = 0 ]
