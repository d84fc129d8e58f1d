// Deliberately breaks the layering: audio/ (a low module) includes the application layer. The
// build must reject it (the test Layering.UpwardIncludeFails builds this file as part of
// gmg_audio's include context and expects "No such file"). Never part of a normal build.
#include "audio/wav.h"
#include "engine/cli/cli.h"

int gmg_layering_upward() { return gmg::cli_main(0, nullptr); }
