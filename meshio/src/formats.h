#pragma once
// The readers and writers of each format, from and to bytes in memory. Private to meshio;
// mesh_io.cpp picks one by MeshFormat.

#include <filesystem>
#include <optional>
#include <string>
#include <string_view>

#include "ffdkit/meshio/atomic_write.h"
#include "ffdkit/meshio/mesh_io.h"

namespace ffdkit::meshio::detail {

MeshData readPly(std::string_view bytes, const std::string& source);
std::string writePly(const MeshData& mesh, PlyEncoding encoding);

MeshData readObj(std::string_view bytes, const std::string& source);
void writeObj(ByteSink& out, const MeshData& mesh);

MeshData readStl(std::string_view bytes, const std::string& source);
std::string writeStl(const MeshData& mesh);

MeshData readXyz(std::string_view bytes, const std::string& source);
void writeXyz(ByteSink& out, const MeshData& mesh);

MeshData readNpy(std::string_view bytes, const std::string& source);
std::string writeNpy(const MeshData& mesh);

/// `folder`: where external buffers may be read from (nullopt: none allowed).
MeshData readGltf(std::string_view bytes, bool binary, const std::string& source,
                  const std::optional<std::filesystem::path>& folder);

MeshData readLegacyVtk(std::string_view bytes, const std::string& source);
MeshData readVtp(std::string_view bytes, const std::string& source);
std::string writeVtk(const MeshData& mesh, bool xml);

}  // namespace ffdkit::meshio::detail
