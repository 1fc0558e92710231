#!/usr/bin/env bash
# End-to-end check of motion.html in a real browser: plans the bundled pendulum examples with the CLI, writes
# their view files, writes pages for hand-made records (a human with a contact and a support rectangle),
# then opens every page in headless Chromium (tests/browser/viewer.mjs). Screenshots land in
# target/browser-artifacts/ with the plan directories (viewer.png is the pendulum's).
#
# Needs Debian's chromium (installed here when missing, as root or through sudo), node and npm.
set -euo pipefail
cd "$(dirname "$0")/.."
repo=$(pwd)

if [ ! -x /usr/bin/chromium ]; then
    echo "+ installing chromium (Debian package)"
    sudo=""
    [ "$(id -u)" -eq 0 ] || sudo="sudo"
    $sudo apt-get update
    DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y --no-install-recommends chromium
fi

echo "+ npm ci (tests/browser)"
(cd tests/browser && npm ci --no-audit --no-fund --loglevel=error)

echo "+ cargo build --release"
cargo build --release --bin mintorque

# Plan directories go beside the screenshots, so that a failure can be looked at afterwards.
artifacts="$repo/target/browser-artifacts"
mkdir -p "$artifacts"
for task in pendulum double_pendulum weight_lift_earth dip_down_space moon_overhead_reach twist_lift astronaut_handrail; do
    echo "+ mintorque plan examples/$task.toml"
    rm -rf "$artifacts/plan-$task"
    cargo run --release --quiet --bin mintorque -- plan "examples/$task.toml" --out "$artifacts/plan-$task" --quiet
done

echo "+ cargo test --release --test viewer writes_pages_for_the_browser_test"
cargo test --release --test viewer writes_pages_for_the_browser_test

echo "+ node tests/browser/viewer.mjs"
ARTIFACTS_DIR="$artifacts" node tests/browser/viewer.mjs \
    "$artifacts/plan-pendulum/motion.html" "$artifacts/plan-double_pendulum/motion.html" \
    "$artifacts/plan-weight_lift_earth/motion.html" "$artifacts/plan-dip_down_space/motion.html" \
    "$artifacts/plan-moon_overhead_reach/motion.html" "$artifacts/plan-twist_lift/motion.html" \
    "$artifacts/plan-astronaut_handrail/motion.html" \
    "$artifacts/synthetic-human/motion.html" "$artifacts/synthetic-double-pendulum/motion.html" \
    "$artifacts/synthetic-mixed/motion.html"
