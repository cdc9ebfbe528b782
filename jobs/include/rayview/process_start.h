#pragma once
// When this process started, for the start-up figure `rayview render` reports: main() to the first ray, less
// load and build.

namespace rayview {

// Call first thing in main().
void captureProcessStart();

// Milliseconds from captureProcessStart() to now.
double msSinceProcessStart();

}  // namespace rayview
