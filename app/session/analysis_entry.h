// The arch analysis of one jaw as a cache entry (session/oracle_cache.h, kind "analysis"): its
// key, and its bytes both ways. The analysis depends on the mesh alone (analysis/arch_analysis.h),
// so the key is the mesh's content hash, the jaw, the options and the analysis's code version;
// decoding gives back the analysis bit for bit (every double exactly, every string and order).
#pragma once

#include <cstdint>
#include <stdexcept>
#include <string>
#include <string_view>

#include "analysis/arch_analysis.h"
#include "occlude/io/triangle_mesh.h"

namespace occlude::app {

/// The cache entry kind of arch analyses.
inline constexpr char kArchAnalysisEntryKind[] = "analysis";

/// The key of AnalyzeArch(mesh, jaw, options) (io::MeshContentHash of the mesh, the jaw, every
/// option, analysis::ArchAnalysisCodeVersion() and this encoding's version).
std::uint64_t ArchAnalysisKey(const io::TriangleMesh& mesh, io::Jaw jaw,
                              const analysis::ArchAnalysisOptions& options);

/// The analysis as bytes (JSON; doubles in their shortest round-trip form).
std::string EncodeArchAnalysis(const analysis::ArchAnalysis& a);
/// The analysis EncodeArchAnalysis wrote; throws std::runtime_error saying what is malformed.
analysis::ArchAnalysis DecodeArchAnalysis(std::string_view bytes);

}  // namespace occlude::app
