// The control of pipeline_includes_cli.cpp and pipeline_includes_render.cpp: the pipeline's include
// context with only its declared dependencies (config, the analysis and graph modules) builds. So
// the checks above fail for the include alone.
#include "engine/config/config.h"
#include "engine/core/parallel.h"
#include "engine/pipeline/pipeline.h"
#include "graph/graph_io.h"

int gmg_layering_pipeline_allowed() { return gmg::worker_count(1, 1) + static_cast<int>(sizeof(gmg::Config)); }
