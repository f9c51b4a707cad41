#include "isolated_import.h"

#include "imported_mesh_codec.h"
#include "wirerig/rig/isolated_process.h"

namespace wirerig {

Result<ImportedMesh> ImportMeshIsolated(const std::filesystem::path& path,
                                        const ImportOptions& options) {
  ImportOptions in_child = options;
  in_child.isolation.reset();
  Result<std::string> answer = RunIsolated(path, *options.isolation, [&]() -> Result<std::string> {
    Result<ImportedMesh> imported = ImportMesh(path, in_child);
    if (!imported) return Error{imported.error()};
    return EncodeImportedMesh(imported.value());
  });
  if (!answer) return Error{answer.error()};
  Result<ImportedMesh> decoded = DecodeImportedMesh(answer.value());
  if (!decoded)
    return Error{path.string() + ": the importer process answered badly: " + decoded.error()};
  return decoded;
}

}  // namespace wirerig
