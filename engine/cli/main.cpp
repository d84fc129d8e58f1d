// gmg: the gesture motion graph command-line tool.
#include "engine/cli/cli.h"

#ifdef GMG_JEMALLOC
// The command's memory allocator is jemalloc (linked in place of the C library's malloc, see
// GMG_JEMALLOC in CMakeLists.txt), which reads this string when it starts, before main; MALLOC_CONF
// in the environment adds to it and wins.
//
// A command's large arrays (the samples, the motion, the pose features, the spectrogram) are each
// touched for the first time once, and on a virtual machine a first touch costs a page fault per
// 4 KiB page. thp:always asks the kernel (with madvise, which its "madvise" mode of transparent
// huge pages honours) to back jemalloc's memory with 2 MiB pages where it can, so that a first
// touch faults and clears 2 MiB at a time (the faults counted: docs/performance.md). The C
// library's malloc maps each large array on its own 4 KiB pages and has no such setting a program
// can make for itself.
extern "C" {
// NOLINTNEXTLINE(cppcoreguidelines-avoid-non-const-global-variables): the name and type jemalloc reads.
const char* malloc_conf = "thp:always,metadata_thp:auto";
}
#endif

int main(int argc, char** argv) { return gmg::cli_main(argc, argv); }
