#pragma once
// The two drivers of a render job in one process (private to jobs/): runRenderJob picks one.

#include "rayview/render_job.h"

namespace rayview {

// One image of one scene: open, build, render, write, report.
int runSingleRender(const RenderJob& job);

// Frames: a turntable, a batch, a CENG477 file's cameras into a directory (rayview/frame_plan.h).
int runFramesJob(const RenderJob& job);

}  // namespace rayview
