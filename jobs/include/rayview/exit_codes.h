#pragma once
// rayview's exit statuses, the same for every subcommand and for the viewer.

namespace rayview {

inline constexpr int kExitOk = 0;
inline constexpr int kExitIoFailure = 1;
inline constexpr int kExitBadInput = 2;  // bad scene or bad arguments; nothing written
inline constexpr int kExitOutOfMemory = 3;  // an allocation failed; a clear message, nothing written

}  // namespace rayview
