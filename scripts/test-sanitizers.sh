#!/usr/bin/env bash
# The test suite under AddressSanitizer and UndefinedBehaviorSanitizer: builds the test
# programs (dynrad_tests, path_tracer_tests, mesh_tracer_tests) and the dynrad command line they run (clang,
# -O1, assertions on) into build-fuzz, then runs the tests with ctest. The first sanitizer error fails its test
# (halt_on_error; the dynrad processes the tests start inherit the same options).
#
#   scripts/test-sanitizers.sh        # every test (about an hour on 2 cores)
#   scripts/test-sanitizers.sh --ci   # CI: every test but the long physics runs below
#
# Sanitized code runs about 6 times slower than a release build. With --ci, the physics
# tests that solve whole rooms to convergence (3 tests x 3 methods, and the energy
# check for adaptive: 4 to 25 minutes each here), the two that compare whole solves
# with and without simplification or culling, and the two that compare rooms built on
# slabs with clean ones (imprint_physics_test: 40-90 s each sanitized), the storey, the
# 100,000 materials, the three quality levels of the error estimate, adaptive's hidden
# parts (155 s sanitized), a luminaire's umbra over a finely refined floor (71 s) and
# shaped against even senders (51 s), the CIE 171 validation (116 solves; one
# section of it, validate_sections, runs sanitized), the light scene against a direct
# solve (two converged storey solves, 380 s sanitized) and the storey's PDF through
# `grid` (210 s; the storey's PDF through `solve`, DesignCli, runs sanitized), the
# daylight coefficients against four converged solves (90 s in release) and a year of
# daylight on the daylit room (50 s in release; the annual command's refusals run
# sanitized), sender groups' exact light (38 s in release; their thread-count test runs
# sanitized) and the steering sky through its channels (24 s in release; an hour's
# direct sky through the coefficients runs sanitized), the IFC house against its path-traced
# reference (30 s in release), the rooms joined by a door against the mesh tracer (20 s)
# and the storey with its faces reordered (two full solves; the same storey by three
# paths runs sanitized) are left to the release suite; the
# furnace and per-shot energy tests, every command-line solve and every other test run
# sanitized, so every solver path (progressive, adaptive, dynamic) still does.
#
# Embree and oneTBB are uninstrumented system libraries; the only allowance for them is
# tests/lsan.supp (memory they keep until exit). Nothing else is switched off.
set -euo pipefail
cd "$(dirname "$0")/.."
root=$(pwd)
# The C library's tests (capi_test and the Blender add-on's, which load libdynrad.so
# into Blender's own Python, where no ASan runtime is loaded) and `import dynrad`'s
# (the same: Python has no ASan runtime) are not run here; they run in the release
# suite. The solver and import code they call run sanitized through
# dynrad_tests.
hosts='capi_test|blender_|browser_walk|BrowserView\.|python_'
exclude=(-E "$hosts")
if [ "${1:-}" = "--ci" ]; then
  exclude=(-E "$hosts|Physics\.(ClosedRoomReflectsAllPowerUntilAbsorbed|NoLightThroughAWallSharedByTwoRooms|CornellFloorIsRedderNextToTheRedWall)/|Physics\.EnergyIsConservedAfterEveryShot/adaptive|Simplify\.SolveAgreesWithAndWithoutSimplification|Culling\.NegligibleReceiversCostAtMostTheirStatedShare|Junctions\.FloorByTheWallsIsLitAsIfItEndedThere/|BoxOnTheFloor\.|Storey\.|HostileInput\.HundredThousandMaterialsLoadInSeconds|ErrorEstimate\.BoundsTheMeasuredErrorOnThe1990RoomForEveryQuality|Junctions\.HiddenPartsTakeNoLightAndTheBalanceHolds/adaptive|Luminaire\.PlateCastsAnUmbraWithNoDirectLight|ShapedSenders\.CloserToAFineSolutionThanEvenSenders|Views\.PreviewInsideAClosedBuildingIsNotBlack|Daylight\.GlazingScalesTheWholeSolveAndTheBalanceHolds|AssimpImport\.IfcHouseHasItsElementsStandsUpAndLights|DesignCli\.LightSceneEqualsASolveOfTheSameDimming|PdfGridCommand\.WritesA4ReportWithEachGrid|NoLostWork\.LongShotShowsProgressAndAStopWaitsForItsEnd|validate_cie171|DaylightCoefficients\.OneSolvesCoefficientsGiveEachHoursOwnSolve|AnnualCli\.AClearYearOnTheDaylitRoom|AnnualCli\.AStoppedSolveStillGivesTheYearFromTheLightSoFar|SenderGroups\.SendExactlyTheLightOfTheirPatches|DaylightCoefficients\.TheSteeringSkyThroughItsChannelsIsItsOwnSolve|HouseReference\.|LightBetweenRooms\.|InputIndependence\.FacesInAnotherOrder")
elif [ $# -gt 0 ]; then
  echo "usage: $0 [--ci]" >&2
  exit 2
fi
scripts/install-deps.sh
# The same build directory as scripts/fuzz.sh (scripts/configure-reliability.sh): CI runs
# both, and the library compiled once with clang, ASan, UBSan and libFuzzer's coverage
# serves the tests and the fuzz targets (a second sanitized build of the library cost
# CI about six minutes).
scripts/configure-reliability.sh
cmake --build build-fuzz --parallel "$(nproc)" --target dynrad dynrad_tests path_tracer_tests mesh_tracer_tests

export ASAN_OPTIONS=halt_on_error=1:detect_leaks=1:strict_string_checks=1:check_initialization_order=1
export UBSAN_OPTIONS=halt_on_error=1:print_stacktrace=1
export LSAN_OPTIONS=suppressions=$root/tests/lsan.supp:print_suppressions=0
ctest --test-dir build-fuzz --output-on-failure --parallel "$(nproc)" --timeout 3600 "${exclude[@]}"
