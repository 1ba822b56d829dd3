// The arch analysis of a case: both jaws of a jaw pair analysed once, each in its own frame (the
// lower in L, the upper in U), given landmarks overriding the detected ones, and the clinical
// relationships of ../shared/docs/clinical.md at any pose of the upper jaw. The analysis does not
// depend on the pose, so a command analyses once and measures at every pose it reports.
#pragma once

#include <Eigen/Geometry>
#include <filesystem>
#include <vector>

#include "analysis/arch_analysis.h"
#include "analysis/relationships.h"
#include "occlude/io/dental.h"
#include "session/jaw_pair.h"

namespace occlude::app {

/// Both jaws analysed once (each in its own frame: lower in L, upper in U), given landmarks
/// (if any) overriding detected ones per jaw/tooth/type.
struct CaseAnalysis {
  analysis::ArchAnalysis lower_L;
  analysis::ArchAnalysis upper_U;
  bool has_given_landmarks = false;
};

class OracleCache;

/// The arch analysis of one jaw (analysis::AnalyzeArch with the default options), from `cache`
/// when it holds this mesh's (session/analysis_entry.h), else made and saved there (null: made).
analysis::ArchAnalysis AnalyzeJaw(const io::TriangleMesh& mesh, io::Jaw jaw, OracleCache* cache);

/// Both jaws at once through AnalyzeJaw.
/// `given`: landmarks as read by io::ReadLandmarkFile, lower ones in L, upper ones in U (the
/// frame of `pair.upper_U`: for a pair re-expressed by AtReference, the upper ones moved by the
/// original X_LU_ref first, see GivenAtReference). A jaw on which no tooth is found gives an
/// analysis whose `error` says so; its given landmarks are still applied.
CaseAnalysis AnalyzeCase(const JawPair& pair, const std::vector<io::Landmark>& given = {},
                         OracleCache* cache = nullptr);

/// The clinical relationships with the upper jaw at X_LU (frame from the landmarks when
/// given, else the lower arch frame, as ComputeRelationships decides).
analysis::Relationships RelationshipsAt(const CaseAnalysis& a, const Eigen::Isometry3d& X_LU);

/// Every landmark of both jaws with its point in L with the upper jaw at X_LU: the lower ones
/// first, then the upper ones moved by X_LU, each jaw in its analysis's order.
std::vector<analysis::ArchLandmark> LandmarksInL(const CaseAnalysis& a,
                                                 const Eigen::Isometry3d& X_LU);

/// A frame in L to look at the arches in: the relationships' frame when there is one, else the
/// upper arch frame at X_LU (anatomical: occlusal lower -> upper), else L's axes.
analysis::ArchFrame ViewFrame(const CaseAnalysis& a, const analysis::Relationships& r,
                              const Eigen::Isometry3d& X_LU);

/// Given landmarks of a pair's files re-expressed for the pair AtReference(pair): the upper
/// ones moved by the pair's X_LU_ref (they move with the upper jaw), the lower ones as they are.
std::vector<io::Landmark> GivenAtReference(const Eigen::Isometry3d& X_LU_ref,
                                           std::vector<io::Landmark> given);

/// io::ReadLandmarkFile(file) with its error (one line naming the file, line and field) as a
/// UserError.
std::vector<io::Landmark> ReadGivenLandmarks(const std::filesystem::path& file);

}  // namespace occlude::app
