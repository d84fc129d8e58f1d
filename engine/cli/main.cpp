// gmg: the gesture motion graph command-line tool.
#include "engine/cli/cli.h"

int main(int argc, char** argv) { return gmg::cli_main(argc, argv); }
