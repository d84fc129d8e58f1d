// The command-line tool's entry point, in the library so tests can drive it in-process.
#pragma once

namespace gmg {

// Parses argv, runs one subcommand, prints errors as one line on stderr. Returns the exit code.
int cli_main(int argc, char** argv);

}  // namespace gmg
