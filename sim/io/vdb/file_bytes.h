#pragma once
// What every .vdb file spume writes shares: OpenVDB initialised once, Blosc compression, "creator:
// spume", and bytes that depend only on the grids. OpenVDB stamps each file with a random UUID; spume
// puts one derived from the rest of the file (same content, same UUID). Includes OpenVDB's heavy
// headers: only the module's files include this.
#include <string>

#include <openvdb/openvdb.h>

namespace spume::openvdb_io {

// OpenVDB initialised once, with the codecs spume reads that it does not register (Mantaflow's
// truncated int32 flag); every reader and writer of the module calls it first.
void initialize_openvdb();

// The whole file for `grids`, as bytes.
std::string vdb_file_bytes(const openvdb::GridCPtrVec& grids);

}  // namespace spume::openvdb_io
