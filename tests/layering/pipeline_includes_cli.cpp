// Deliberately breaks the layering: the pipeline (the library a program without the command line
// links) includes the command line. The build must reject it (Layering.PipelineCannotIncludeTheCli
// builds this file in gmg_pipeline's include context and expects "No such file"). Never part of a
// normal build.
#include "engine/cli/cli.h"
#include "engine/pipeline/pipeline.h"

int gmg_layering_pipeline_includes_cli() { return gmg::cli_main(0, nullptr); }
