#pragma once
// `rayview compare IMAGE REFERENCE [--diff OUT.png] [--min-within1 P]`: how far an image is from a reference.

#include "command_line.h"

namespace rayview {

// Prints `exact=E% within1=W% maxdiff=M psnr=P`; returns 0 when at least command.minWithin1 % of the pixels are
// within 1 of the reference, 1 when not, 2 for an unreadable image or images of different sizes.
int runCompareCommand(const CommandLine& command);

}  // namespace rayview
