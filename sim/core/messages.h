#pragma once
// What a command tells its user on stderr besides its result, by kind:
// - progress (core/progress.h), rewritten in place on a terminal;
// - notes: what was derived or done ("domain: ...", "diffuse: simulating (...)");
// - warnings: a result may be wrong, or an input looks wrong ("warning: ...").
// `--quiet` hides progress and notes, never warnings (nor errors, which main prints). A farm job runs
// quiet; a warning lost there would make a wrong result look like a clean one.
//
// Each distinct warning is printed once per process and kept in order, so that a stage can store the
// warnings behind its outputs in its record (io/stage_record.h) and say them again when a later run
// reuses those outputs. One stream per process: the lines come from every stage and from parallel
// readers, and must not interleave or break an open progress line.
#include <cstddef>
#include <string>
#include <vector>

namespace spume::messages {

inline constexpr const char* kWarningPrefix = "warning: ";

void set_quiet(bool quiet);
bool quiet();

// A routine line; printed unless quiet.
void note(const std::string& line);
// Printed whatever quiet says, the first time this text is given; `line` with or without the
// "warning: " prefix (it is added when missing).
void warning(const std::string& line);
// A line of a mixed list (notes and warnings made as text, e.g. SceneInputs::notes): a warning when
// it starts with "warning:", else a note.
void report(const std::string& line);
bool is_warning(const std::string& line);

// Every distinct warning given so far in this process, in order, with its prefix.
std::vector<std::string> warnings();
// The warnings given after the first `from` (warnings().size() at some earlier point).
std::vector<std::string> warnings_since(size_t from);

// For Progress: a progress line, rewritten in place when `in_place` (a terminal), and the end of one.
// Notes and warnings end an open in-place line before they print.
void progress_line(const std::string& line, bool in_place);
void end_progress_line();

// Tests: forget the warnings given so far and be loud again.
void reset();

}  // namespace spume::messages
