// The dental vocabulary every part of occlude shares (../shared/docs/clinical.md): the two
// jaws, tooth numbers (FDI / ISO 3950, and the Universal numbers of 3Shape part files) and the
// landmark types, with their names as they appear in landmark files and outputs.
//
// FDI: 11-18 upper right, 21-28 upper left, 31-38 lower left, 41-48 lower right (the second
// digit counts from the midline: 1 central incisor ... 8 third molar). Universal: 1-16 upper
// from the patient's right third molar (18) to the left one (28), 17-32 lower from the left
// third molar (38) to the right one (48).
#pragma once

#include <Eigen/Core>
#include <optional>
#include <string>

namespace occlude::io {

enum class Jaw { kUpper, kLower };
/// "upper" or "lower".
const char* ToString(Jaw jaw);
/// Parses "upper" / "lower"; nullopt otherwise.
std::optional<Jaw> JawFromName(const std::string& name);

/// True for 11-18, 21-28, 31-38, 41-48.
bool IsValidFdi(int fdi);
/// The jaw of a valid FDI number (quadrants 1-2 upper, 3-4 lower).
Jaw JawOfFdi(int fdi);
/// FDI number of a Universal number 1-32; std::invalid_argument naming "universal" otherwise.
int FdiFromUniversal(int universal);
/// Universal number of a valid FDI number; std::invalid_argument naming "fdi" otherwise.
int UniversalFromFdi(int fdi);
/// Position of the tooth counted from the midline: the FDI number's second digit (1 central
/// incisor, 3 canine, 4-5 premolars, 6-8 molars).
inline int ToothPosition(int fdi) { return fdi % 10; }
/// True for the patient's left side (quadrants 2 and 3).
inline bool IsLeftSide(int fdi) { return fdi / 10 == 2 || fdi / 10 == 3; }

/// The landmark types of clinical.md.
enum class LandmarkType {
  kMesial,            ///< "mesial": mesial contact point
  kDistal,            ///< "distal": distal contact point
  kFacial,            ///< "facial": mid-crown point of the facial (buccal/labial) surface
  kLingual,           ///< "lingual": mid-crown point of the lingual surface
  kIncisalEdge,       ///< "incisal_edge": incisors, midpoint of the incisal edge
  kCuspTip,           ///< "cusp_tip": canines
  kBuccalCusp,        ///< "buccal_cusp": premolars
  kLingualCusp,       ///< "lingual_cusp": premolars
  kMbCusp,            ///< "mb_cusp": molars, mesiobuccal cusp
  kMiddleBuccalCusp,  ///< "middle_buccal_cusp": lower molars
  kDbCusp,            ///< "db_cusp": molars, distobuccal cusp
  kMlCusp,            ///< "ml_cusp": molars, mesiolingual cusp
  kDlCusp,            ///< "dl_cusp": molars, distolingual cusp
  kCentralFossa,      ///< "central_fossa"
};
inline constexpr int kNumLandmarkTypes = 14;
/// The file name of a type ("mb_cusp").
const char* ToString(LandmarkType type);
/// Parses a file name of a type; nullopt for an unknown name.
std::optional<LandmarkType> LandmarkTypeFromName(const std::string& name);
/// Every type's name, comma-separated (for error messages).
std::string LandmarkTypeNames();

/// One landmark: a point on a tooth of one jaw, in the frame of that jaw's mesh (mm).
struct Landmark {
  Jaw jaw = Jaw::kLower;
  int tooth_fdi = 0;
  LandmarkType type = LandmarkType::kMesial;
  Eigen::Vector3d p = Eigen::Vector3d::Zero();
};

}  // namespace occlude::io
