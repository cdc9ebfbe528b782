#pragma once
// The conformance scenes in rayview's own format: shared/conformance/ceng477/*.xml without the course's
// original *.ceng477.xml copies, sorted by name.

#include <filesystem>
#include <vector>

namespace rayview::testing {

std::vector<std::filesystem::path> conformanceScenePaths();

}  // namespace rayview::testing
