#include "render/app/read_check_command.h"

#include <tbb/global_control.h>

#include <cstdio>
#include <filesystem>
#include <new>

#include "sim/core/error.h"
#include "sim/core/out_of_memory.h"
#include "sim/io/contained_read.h"
#include "sim/io/vdb_module.h"
#include "sim/io/vdb_points.h"

namespace spume {

int run_read_check(const std::vector<std::string>& args) {
  if (args.size() != 3 || args[0] != "vdb") {
    std::fprintf(stderr, "spume: error: %s expects FORMAT FILE GRID with FORMAT vdb\n", kReadCheckWord);
    return 2;
  }
  const std::filesystem::path path = args[1];
  try {
    // OpenVDB is opened before the limit: its ~60 MB of mappings are not the file's to spend.
    vdb_module();
    // One thread: worker stacks would spend the address space the budget gives the file.
    const tbb::global_control one_thread(tbb::global_control::max_allowed_parallelism, 1);
    std::error_code size_error;
    const uint64_t file_bytes = std::filesystem::file_size(path, size_error);
    limit_this_process_for_a_contained_read(contained_read_budget(size_error ? 0 : file_bytes),
                                            contained_read_seconds(size_error ? 0 : file_bytes));
    read_vdb_contents(path, args[2], nullptr);
    return 0;
  } catch (const Error& e) {
    std::fprintf(stderr, "spume: error: %s\n", e.what());
  } catch (const std::bad_alloc&) {
    std::fprintf(stderr, "spume: error: %s: %s\n", path.c_str(), out_of_memory_message("reading this file").c_str());
  } catch (const std::exception& e) {
    std::fprintf(stderr, "spume: error: %s: %s\n", path.c_str(), e.what());
  }
  return 1;
}

}  // namespace spume
