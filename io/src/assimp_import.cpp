// OBJ and PLY through assimp, after the structural pre-checks. assimp stays
// behind this file: nothing of it reaches a header.
#include <assimp/postprocess.h>
#include <assimp/scene.h>

#include <assimp/Importer.hpp>
#include <climits>
#include <cmath>
#include <exception>

#include "mesh_io_internal.h"
#include "mesh_io_text.h"

namespace occlude::io::detail {
namespace {

namespace fs = std::filesystem;

// Re-checks what triangulation will read (indices in range, finite vertices), so
// that assimp's own output is never trusted blindly.
void CheckScene(const fs::path& file, const aiScene& scene) {
  for (unsigned m = 0; m < scene.mNumMeshes; ++m) {
    const aiMesh& mesh = *scene.mMeshes[m];
    for (unsigned v = 0; v < mesh.mNumVertices; ++v) {
      const aiVector3D& p = mesh.mVertices[v];
      if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z)) {
        Fail(file,
             "a vertex has a non-finite coordinate (NaN or infinity); the file is corrupt: "
             "export it again");
      }
    }
    for (unsigned f = 0; f < mesh.mNumFaces; ++f) {
      const aiFace& face = mesh.mFaces[f];
      for (unsigned k = 0; k < face.mNumIndices; ++k) {
        if (face.mIndices[k] >= mesh.mNumVertices) {
          Fail(file, "a face refers to vertex " + std::to_string(face.mIndices[k]) +
                         " but the mesh has only " + std::to_string(mesh.mNumVertices) +
                         " vertices; the file is corrupt: export it again");
        }
      }
    }
  }
}

// Triangles of all meshes, in assimp's mesh order; points and lines are counted
// and left out.
RawMesh Collect(const fs::path& file, const aiScene& scene) {
  RawMesh raw;
  std::size_t skipped = 0;
  for (unsigned m = 0; m < scene.mNumMeshes; ++m) {
    const aiMesh& mesh = *scene.mMeshes[m];
    const std::size_t base = raw.positions.size();
    if (base + mesh.mNumVertices > static_cast<std::size_t>(INT_MAX)) {
      Fail(file, "has too many vertices for 32-bit indices; decimate the mesh");
    }
    for (unsigned v = 0; v < mesh.mNumVertices; ++v) {
      const aiVector3D& p = mesh.mVertices[v];
      raw.positions.emplace_back(static_cast<double>(p.x), static_cast<double>(p.y),
                                 static_cast<double>(p.z));
    }
    for (unsigned f = 0; f < mesh.mNumFaces; ++f) {
      const aiFace& face = mesh.mFaces[f];
      if (face.mNumIndices != 3) {
        ++skipped;
        continue;
      }
      raw.triangles.emplace_back(static_cast<int>(base + face.mIndices[0]),
                                 static_cast<int>(base + face.mIndices[1]),
                                 static_cast<int>(base + face.mIndices[2]));
    }
  }
  if (skipped > 0) {
    raw.warnings.push_back(Line(file, "ignored " + std::to_string(skipped) +
                                          " point or line elements; only faces make the surface"));
  }
  return raw;
}

}  // namespace

RawMesh ImportWithAssimp(const fs::path& file, std::string_view bytes, const char* hint) {
  Assimp::Importer importer;
  const aiScene* scene = nullptr;
  try {
    // No post-processing yet: CheckScene runs before triangulation reads anything.
    scene = importer.ReadFileFromMemory(bytes.data(), bytes.size(), 0, hint);
    if (scene != nullptr) {
      CheckScene(file, *scene);
      scene = importer.ApplyPostProcessing(aiProcess_Triangulate);
    }
  } catch (const MeshError&) {
    throw;
  } catch (const std::exception& e) {
    Fail(file, std::string("the importer failed: ") + e.what());
  }
  if (scene == nullptr) {
    Fail(file, std::string("cannot be read as ") + hint + ": " + importer.GetErrorString());
  }
  return Collect(file, *scene);
}

RawMesh ReadObj(const fs::path& file, std::string_view bytes) {
  return ImportWithAssimp(file, CanonicalObjText(file, WithoutUtf8Bom(bytes)), "obj");
}

RawMesh ReadPly(const fs::path& file, std::string_view bytes) {
  bytes = WithoutUtf8Bom(bytes);
  std::vector<std::string> warnings;
  const std::string canonical = CanonicalPlyBytes(file, bytes, &warnings);
  RawMesh raw = ImportWithAssimp(file, canonical, "ply");
  raw.warnings.insert(raw.warnings.begin(), warnings.begin(), warnings.end());
  return raw;
}

}  // namespace occlude::io::detail
