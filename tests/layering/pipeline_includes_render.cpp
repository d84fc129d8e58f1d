// Deliberately breaks the layering: the pipeline includes the render library, which links cairo
// and drives ffmpeg; those stay with the commands that draw. The build must reject it
// (Layering.PipelineCannotIncludeRender expects "No such file"). Never part of a normal build.
#include "engine/pipeline/pipeline.h"
#include "engine/render/render.h"

int gmg_layering_pipeline_includes_render() { return static_cast<int>(sizeof(gmg::render::RenderSummary)); }
