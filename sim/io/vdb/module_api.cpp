// The module's table (io/vdb_module.h): its one exported symbol.
#include "sim/io/vdb/openvdb_io.h"
#include "sim/io/vdb_module.h"

extern "C" __attribute__((visibility("default"))) const spume::VdbModuleApi* spume_vdb_module_api() {
  namespace io = spume::openvdb_io;
  static const spume::VdbModuleApi api{spume::vdb_module_layout(), io::read_contents, io::read_points,
                                       io::points_bytes, io::fog_bytes};
  return &api;
}
