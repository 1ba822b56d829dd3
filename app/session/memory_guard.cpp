// The commands' memory guard (see memory_guard.h).
#include "session/memory_guard.h"

#include <cmath>
#include <sstream>

#include "base/user_error.h"
#include "occlude/collision/morton.h"

namespace occlude::app {
namespace {

constexpr double kBytesPerMb = 1e6;

// x rounded up to two significant digits, so that the size named still fits.
double RoundUpTwoDigits(double x) {
  const double scale = std::pow(10.0, std::floor(std::log10(x)) - 1.0);
  return std::ceil(x / scale * (1.0 - 1e-12)) * scale;
}

std::string Number(double x) {
  std::ostringstream s;
  s.precision(3);
  s << x;
  return s.str();
}

// Voxels a grid may have along an axis (the Morton key range), less the padding
// the voxelizer and the fields add on both sides.
constexpr double kGridVoxels = static_cast<double>(collision::kMortonMaxCoord) - 16.0;

// The grid check: one line naming the mesh when its grid would not fit.
void CheckGrid(const MemoryCheck& check, double voxel_mm) {
  for (const MeshExtent& mesh : check.meshes) {
    const double smallest = mesh.extent_mm / kGridVoxels;
    if (smallest > check.max_voxel_mm) {
      throw UserError(mesh.name + ": the mesh spans " + Number(mesh.extent_mm) +
                      " mm, too large for a voxel grid at any voxel size up to " +
                      Number(check.max_voxel_mm) + " mm (at most " + Number(kGridVoxels) +
                      " voxels along an axis); check the file's units and coordinates");
    }
    if (voxel_mm < smallest) {
      throw UserError(
          mesh.name + ": voxel grid too large: the mesh spans " + Number(mesh.extent_mm) +
          " mm, which at voxel " + Number(voxel_mm) + " mm needs " +
          Number(mesh.extent_mm / voxel_mm) + " voxels along an axis (at most " +
          Number(kGridVoxels) + "); the smallest voxel size that fits is about " +
          Number(RoundUpTwoDigits(smallest)) + " mm: set " + check.voxel_fix + " to at least that");
    }
  }
}

}  // namespace

std::string JawFilesName(const std::vector<std::string>& files) {
  if (files.empty()) return "(no files)";
  return files.size() == 1
             ? files.front()
             : files.front() + " + " + std::to_string(files.size() - 1) + " more part files";
}

MeshExtent ExtentOf(const std::string& name, const io::TriangleMesh& mesh) {
  return {name, mesh.empty() ? 0.0 : mesh.Bounds().sizes().maxCoeff()};
}

std::string Megabytes(std::size_t bytes) {
  const double mb = static_cast<double>(bytes) / kBytesPerMb;
  std::ostringstream s;
  s.precision(mb >= 10 ? 0 : 1);
  s << std::fixed << mb << " MB";
  return s.str();
}

MemoryBudget ResolveMemoryBudget(double option_mb, std::optional<double> config_mb) {
  if (option_mb > 0)
    return {static_cast<std::size_t>(option_mb * kBytesPerMb), "--memory-budget-mb"};
  if (config_mb)
    return {static_cast<std::size_t>(*config_mb * kBytesPerMb), "limits.memory_budget_mb"};
  const std::size_t bytes = collision::DefaultMemoryBudgetBytes();
  return {bytes, "the default, a quarter of the physical memory"};
}

std::function<collision::MemoryEstimate(double voxel_mm)> SphereTreePairEstimate(
    const io::TriangleMesh& lower, const io::TriangleMesh& upper,
    const collision::SphereTreeOptions& options) {
  return [&lower, &upper, options](double voxel_mm) {
    collision::SphereTreeOptions o = options;
    o.voxelize.voxel_size_mm = voxel_mm;
    collision::MemoryEstimate e = collision::EstimateSphereTreeMemory(lower, o);
    e += collision::EstimateSphereTreeMemory(upper, o);
    return e;
  };
}

void CheckMemory(const MemoryCheck& check,
                 const std::function<collision::MemoryEstimate(double voxel_mm)>& estimate,
                 double voxel_mm, const MemoryBudget& budget) {
  CheckGrid(check, voxel_mm);
  const collision::MemoryEstimate need = estimate(voxel_mm);
  if (need.peak_bytes <= budget.bytes) return;
  const auto peak = [&](double s) { return estimate(s).peak_bytes; };
  const double fit =
      collision::SmallestFittingVoxelMm(peak, voxel_mm, check.max_voxel_mm, budget.bytes);
  std::ostringstream s;
  s << check.subject << ": building " << check.building << " at voxel " << Number(voxel_mm)
    << " mm needs about " << Megabytes(need.peak_bytes) << ", over the memory budget of "
    << Megabytes(budget.bytes) << " (" << budget.source << "); ";
  if (std::isfinite(fit)) {
    const double suggested = std::min(RoundUpTwoDigits(fit), check.max_voxel_mm);
    s << "the smallest voxel size that fits is about " << Number(suggested) << " mm: set "
      << check.voxel_fix << " to at least that";
  } else {
    s << "no voxel size up to " << Number(check.max_voxel_mm) << " mm fits: " << check.no_fit_fix;
  }
  s << ", or raise the budget with --memory-budget-mb or limits.memory_budget_mb";
  throw UserError(s.str());
}

}  // namespace occlude::app
