#pragma once
// The process's heap for a lean scene (rayview/lean_memory.h).

#include <cstddef>

namespace rayview {

// Takes the heap off transparent huge pages, and malloc's big blocks into mappings of their own, from now on (once a
// process), and hands back what the heap holds free (at every call). For the command line only: the viewer keeps its
// huge pages.
void useLeanHeap();

// LoadOptions::beforeArrays for the command line: useLeanHeap() when the loader's estimate of the triangles says the
// scene is lean, before the scene's arrays are allocated.
void useLeanHeapForEstimate(std::size_t estimatedTriangles);

}  // namespace rayview
