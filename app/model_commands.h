#pragma once
// `rayview import MODEL -o SCENE.xml` and `rayview export SCENE.xml -o MODEL.obj|.ply|.stl|.gltf|.glb`, both through
// the import worker (rayview/model_client.h).

#include "command_line.h"

namespace rayview {

int runImportCommand(const CommandLine& command);
int runExportCommand(const CommandLine& command);

}  // namespace rayview
