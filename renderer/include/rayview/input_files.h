#pragma once
// The files this process has read or tried to read (every user file goes through file_read.h's reader, which
// records each one it finds here, whether or not it then loads), so that no write ever replaces one of them by any
// path: writeFileAtomically refuses such an output, as do the commands' own checks before they start work.

#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

namespace rayview {

// What the recent-files list is recorded as: the one input its owner may replace (RecentFiles::save).
inline constexpr std::string_view kRecentFilesRole = "the viewer's recent-files list";

// Records `path` (its device and inode, found with stat: any spelling, link or symlink of it) as `role`, e.g.
// "the scene file". Nothing is recorded when the path does not exist. Thread-safe.
void rememberInput(const std::filesystem::path& path, std::string_view role);

// Why writing `output` would replace a file recorded by rememberInput ("" when it would not): "the output X is the
// scene file Y; choose another name". A file recorded as `mayReplaceRole` (non-empty) is not refused.
std::string outputReplacesInput(const std::filesystem::path& output, std::string_view mayReplaceRole = {});

// Forgets `path` (by any spelling): a command that read one of its own earlier outputs only to see whether it is
// whole (a frame of a resumed turntable) may then replace it.
void forgetInput(const std::filesystem::path& path);

// Every recorded file as "role" and path, in the order recorded: what the import worker tells rayview it read.
struct RememberedInput {
  std::string role;
  std::string path;
};
std::vector<RememberedInput> rememberedInputs();

// Forgets every recorded file: for tests that reuse one name for a new input.
void forgetInputs();

}  // namespace rayview
