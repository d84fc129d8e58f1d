// The engine's jobs: analyse speech into timed events (speech_analysis.h), build a graph from
// reference files or clips in memory (graph_from_files.h), reenact new speech from a graph
// (reenact.h, joining the plan's paths with assembly.h). The command-line tool, batch runs and the
// Python module call these; this header gathers them.
#pragma once

#include "engine/pipeline/assembly.h"
#include "engine/pipeline/graph_from_files.h"
#include "engine/pipeline/reenact.h"
#include "engine/pipeline/speech_analysis.h"
