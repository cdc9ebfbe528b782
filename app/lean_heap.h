#pragma once
// The process's heap for a lean scene (rayview/lean_memory.h).

#include <cstddef>

namespace rayview {

// Takes the heap off transparent huge pages, and malloc's big blocks into mappings of their own, from now on (once a
// process), and hands back what the heap holds free (at every call). For the command line only: the viewer keeps its
// huge pages.
void useLeanHeap();

// Once the scene and its BVH are released, before the image is made whole for the write: what they freed handed
// back, and huge pages allowed again. The write's big blocks (the image, stb_image_write's filtered copy) are
// mappings of their own, touched whole, so huge pages hold nothing more for them and fault them in ~20 ms less
// at 1920x1080 (docs/PERFORMANCE.md, "thirteenth session").
void useLeanHeapForTheWrite();

// LoadOptions::beforeArrays for the command line: useLeanHeap() when the loader's estimate of the triangles says the
// scene is lean, before the scene's arrays are allocated.
void useLeanHeapForEstimate(std::size_t estimatedTriangles);

}  // namespace rayview
