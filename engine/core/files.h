// File helpers shared by every reader and writer: inputs are regular files read whole
// (file_read.h) or mapped (mapped_file.h), outputs appear complete or not at all (file_write.h),
// never on top of an input (output_checks.h), and no temporary file outlives an interrupted
// process (interrupt.h). This header gathers the four.
#pragma once

#include "engine/core/file_read.h"
#include "engine/core/file_write.h"
#include "engine/core/mapped_file.h"
#include "engine/core/output_checks.h"
