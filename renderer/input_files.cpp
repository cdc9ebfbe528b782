#include "rayview/input_files.h"

#include <sys/stat.h>

#include <mutex>
#include <vector>

namespace rayview {
namespace {

struct Input {
  dev_t device;
  ino_t inode;
  std::string path;
  std::string role;
};

struct Inputs {
  std::mutex mutex;
  std::vector<Input> files;
};

Inputs& inputs() {
  static Inputs instance;
  return instance;
}

}  // namespace

void rememberInput(const std::filesystem::path& path, std::string_view role) {
  struct stat st {};
  if (::stat(path.c_str(), &st) != 0) return;
  Inputs& all = inputs();
  const std::lock_guard lock(all.mutex);
  for (const Input& input : all.files)
    if (input.device == st.st_dev && input.inode == st.st_ino) return;
  all.files.push_back({st.st_dev, st.st_ino, path.string(), std::string(role)});
}

std::string outputReplacesInput(const std::filesystem::path& output, std::string_view mayReplaceRole) {
  struct stat st {};
  if (::stat(output.c_str(), &st) != 0) return {};
  Inputs& all = inputs();
  const std::lock_guard lock(all.mutex);
  for (const Input& input : all.files)
    if (input.device == st.st_dev && input.inode == st.st_ino) {
      if (!mayReplaceRole.empty() && input.role == mayReplaceRole) return {};
      return "the output " + output.string() + " is " + input.role + " " + input.path + "; choose another name";
    }
  return {};
}

void forgetInput(const std::filesystem::path& path) {
  struct stat st {};
  if (::stat(path.c_str(), &st) != 0) return;
  Inputs& all = inputs();
  const std::lock_guard lock(all.mutex);
  std::erase_if(all.files, [&](const Input& input) { return input.device == st.st_dev && input.inode == st.st_ino; });
}

std::vector<RememberedInput> rememberedInputs() {
  Inputs& all = inputs();
  const std::lock_guard lock(all.mutex);
  std::vector<RememberedInput> out;
  for (const Input& input : all.files) out.push_back({input.role, input.path});
  return out;
}

void forgetInputs() {
  Inputs& all = inputs();
  const std::lock_guard lock(all.mutex);
  all.files.clear();
}

}  // namespace rayview
