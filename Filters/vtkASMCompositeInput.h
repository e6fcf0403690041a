// SPDX-License-Identifier: BSD-3-Clause
/**
 * Private helper of vtkASMSimplify and vtkKeyPointError (not wrapped, not
 * installed): a composite input (a vtkMultiBlockDataSet of scans grouped in
 * ParaView, the vtkPartitionedDataSet of a partitioned file, ...) taken as
 * ONE cloud, so that N_s is the count of the whole output and overlapping
 * leaves are thinned together, instead of the executive's default of one
 * run per leaf.
 *
 * The points of every vtkPointSet leaf, in the composite's traversal order,
 * become one vtkPolyData without cells (with the composite's field data): coordinates as floats
 * when every leaf's are floats, else as doubles; the point arrays that every leaf with points has,
 * with the same name, type and number of components and a tuple for each of the leaf's points
 * (vtkDataSetAttributes::FieldList; the others
 * are dropped, and named; global ids are kept as other arrays are), unless only the points are
 * asked for. The ghost flags (vtkGhostType, when valid: GhostFlags) are merged in any case, 0
 * for a leaf without them, so that flagged points are skipped as in a vtkPointSet input. With the
 * origins, two vtkIdType arrays say where each point came from: "vtkOriginalBlockIds", the leaf's
 * flat index in the composite (vtkCompositeDataIterator::GetCurrentFlatIndex), and
 * LeafPointIdsName, the point's id in that leaf. Integer arrays travel to a sample as its
 * representative's tuple (vtkASMPointDataAggregation.h), so the output says
 * which leaf, and which point of it, each sample stands for.
 */
#ifndef vtkASMCompositeInput_h
#define vtkASMCompositeInput_h

#include "vtkSmartPointer.h"

#include <string>
#include <vector>

class vtkCompositeDataSet;
class vtkPolyData;

namespace asmvtk
{
/// The name of the per-point id in its leaf while the merged cloud is
/// simplified (vtkASMSimplify renames it vtkOriginalPointIds afterwards).
extern const char* const LeafPointIdsName;

/// What MergeLeaves carries besides the points.
enum class LeafData
{
  PointsOnly,
  Arrays,           ///< the point arrays every leaf has
  ArraysAndOrigins, ///< and each point's leaf and id in it
};

/// The leaves of `input` as one cloud (see above). `dropped`: the names of
/// the arrays left out because some leaf lacks them or has them otherwise.
/// `skipped` (when given): the leaves that are not point sets, but for
/// datasets without points (an image, a rectilinear grid: their points are
/// not simplified; a table), as "block <flat index> (<class>)".
vtkSmartPointer<vtkPolyData> MergeLeaves(vtkCompositeDataSet* input, LeafData what,
  std::vector<std::string>& dropped, std::vector<std::string>* skipped = nullptr);

/// The warning for a dropped array `name`; `whose` (e.g. " of the simplified
/// (port 1) cloud", or empty) names the input when a filter has two.
std::string DroppedArrayWarning(const std::string& name, const char* whose = "");

/// The warning for a leaf that MergeLeaves left out (`skipped`).
std::string SkippedLeafWarning(const std::string& leaf, const char* whose = "");
} // namespace asmvtk

#endif
