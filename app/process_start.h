#pragma once
// When this process started, for the start-up time `rayview render` reports (issue 8: process start to the
// first ray, less load and build). The launcher (app/launcher.cpp) stamps the moment it starts into the
// environment before it execs rayview-cli; a rayview-cli started directly counts from its main(). Both clocks
// are CLOCK_MONOTONIC, which exec does not reset.

namespace rayview {

// The launcher's stamp: CLOCK_MONOTONIC in nanoseconds, as a decimal number.
inline constexpr char kLaunchStampVariable[] = "RAYVIEW_LAUNCH_NS";

// Nanoseconds on CLOCK_MONOTONIC.
long long monotonicNanoseconds();

// Call first thing in main(): takes the launcher's stamp and removes it from the environment, so that no
// program started later inherits it. A stamp that is missing, malformed or not within the last minute (left
// over in a user's environment) is ignored: the start is then now.
void captureProcessStart();

// Milliseconds from the process's start to now.
double msSinceProcessStart();

// Whether the start is the launcher's (else main()'s).
bool processStartIsLaunch();

}  // namespace rayview
