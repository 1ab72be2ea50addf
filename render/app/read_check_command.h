#pragma once
// `spume __read-check FORMAT FILE GRID`: the child that reads an untrusted file before the spume
// command reads it in-process (sim/io/contained_read.h). Not a user's command: not in the help.
#include <string>
#include <vector>

#include "sim/io/contained_read.h"

namespace spume {

// Reads the file under the limits of a contained read, with one thread. Exit 0: read cleanly; 1:
// "spume: error: MESSAGE" on stderr; otherwise whatever stopped it (abort, the alarm, the limit).
int run_read_check(const std::vector<std::string>& args);

}  // namespace spume
