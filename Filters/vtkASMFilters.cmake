# Body of the ASM::Filters VTK module (vtk.module at the repository root).
#
# vtk_module_build() runs this file from a small staging directory in the
# build tree (see the top-level CMakeLists.txt), so every path below is made
# absolute from this file's own directory, never from CMAKE_CURRENT_SOURCE_DIR.
# Nothing here may use ParaView: the module must also build against plain VTK.

set(_asm_filters_dir "${CMAKE_CURRENT_LIST_DIR}")

# ============================================================================
# SOURCE LISTS: the one place to add files to the module.
# ============================================================================
# Public VTK classes: <Name>.h + <Name>.cxx in Filters/. Their headers are
# installed and wrapped (Python, ParaView client-server).
set(ASM_FILTERS_CLASSES
  vtkASMSimplify
  vtkKeyPointError
)
# Private core, plain C++17 + Eigen, no VTK types: Core/<Name>.h + Core/<Name>.cxx.
# Not wrapped and not installed; included as "Core/<Name>.h" (from the module
# and from Testing/Cxx). Put VTKASMFILTERS_EXPORT (from "vtkASMFiltersModule.h")
# on what the tests use: the module is built with hidden symbol visibility.
set(ASM_FILTERS_CORE
  Grid
  CanonicalOrder
  CellPartition
  CellSize
  CellFrame
  PlaneClusters
  KeyPoints
  Budget
  Simplify
  PaperSimplify
  Unclaimed
  CellNeighbors
  FeatureKeyPoints
  ExactMean
  Lloyd
  Assignment
  Selection
  HoleFilling
  Covering
  SnappedHoles
  FeatureOutput
  FeatureRefine
  FeatureSimplify
  Neighbors
  BlockNeighbors
  Curvature
  Metrics
)
# Private VTK-layer helpers (not wrapped, not installed): <Name>.h + <Name>.cxx
# in Filters/. vtkASMPointDataAggregation: the attribute aggregation;
# vtkASMCompositeInput: a composite input's leaves as one cloud;
# vtkASMSimplifySteps: vtkASMSimplify's parameters, input normals and output;
# vtkASMDistributed*: the MPI communication (VTK::ParallelCore).
set(ASM_FILTERS_PRIVATE
  vtkASMPointDataAggregation
  vtkASMCompositeInput
  vtkASMSimplifySteps
  vtkASMDistributed
  vtkASMDistributedMetrics
)
# Private sources declared in another private header (paths relative to
# Filters/): vtkASMDistributed{Feature,Communication,Redistribute,Fetch}.cxx implement
# parts of vtkASMDistributed.h, Core/NeighborsBuild.cxx the build of
# Core/Neighbors.h's tree, Core/HoleFillingGreedy.cxx a step of
# Core/HoleFillingSteps.h, Core/PlaneLinkage.cxx the single linkage of
# Core/PlaneClusters.h.
set(ASM_FILTERS_EXTRA_SOURCES
  vtkASMDistributedFeature.cxx
  vtkASMDistributedCommunication.cxx
  vtkASMDistributedRedistribute.cxx
  vtkASMDistributedFetch.cxx
  Core/NeighborsBuild.cxx
  Core/HoleFillingGreedy.cxx
  Core/PlaneLinkage.cxx
)
# Header-only private headers, if any (paths relative to Filters/).
set(ASM_FILTERS_EXTRA_PRIVATE_HEADERS
  Core/Common.h
  Core/GridOccupancy.h
  Core/GroupBy.h
  Core/HoleFillingRecords.h
  Core/HoleFillingSteps.h
  Core/NeighborsRanges.h
  Core/Quickselect.h
  Core/SpatialBuckets.h
  vtkASMFilterUtilities.h
)
# ============================================================================

set(_asm_sources)
set(_asm_headers)
foreach (_asm_class IN LISTS ASM_FILTERS_CLASSES)
  list(APPEND _asm_sources "${_asm_filters_dir}/${_asm_class}.cxx")
  list(APPEND _asm_headers "${_asm_filters_dir}/${_asm_class}.h")
endforeach ()

set(_asm_private_headers)
foreach (_asm_private IN LISTS ASM_FILTERS_PRIVATE)
  list(APPEND _asm_sources "${_asm_filters_dir}/${_asm_private}.cxx")
  list(APPEND _asm_private_headers "${_asm_filters_dir}/${_asm_private}.h")
endforeach ()
foreach (_asm_extra IN LISTS ASM_FILTERS_EXTRA_SOURCES)
  list(APPEND _asm_sources "${_asm_filters_dir}/${_asm_extra}")
endforeach ()
foreach (_asm_core IN LISTS ASM_FILTERS_CORE)
  list(APPEND _asm_sources "${_asm_filters_dir}/Core/${_asm_core}.cxx")
  list(APPEND _asm_private_headers "${_asm_filters_dir}/Core/${_asm_core}.h")
endforeach ()
foreach (_asm_header IN LISTS ASM_FILTERS_EXTRA_PRIVATE_HEADERS)
  list(APPEND _asm_private_headers "${_asm_filters_dir}/${_asm_header}")
endforeach ()

vtk_module_add_module(ASM::Filters
  SOURCES         ${_asm_sources}
  HEADERS         ${_asm_headers}
  PRIVATE_HEADERS ${_asm_private_headers})

# vtk_module_add_module only puts the staging directory (and the binary
# directory holding vtkASMFiltersModule.h) on the include path. Add Filters/
# itself, publicly for the build tree, so that the module, the plugin and the
# GoogleTest tests can all say #include "vtkASMSimplify.h" / "Core/Simplify.h".
vtk_module_include(ASM::Filters
  PUBLIC
    "$<BUILD_INTERFACE:${_asm_filters_dir}>")

# The core is C++17; consumers including Core/*.h need it too.
vtk_module_compile_features(ASM::Filters
  PUBLIC
    cxx_std_17)

# Eigen (libeigen3-dev) is header-only and used by the core only: a PRIVATE,
# build-tree-only dependency that an installed module does not carry along.
# (Not VTK::eigen: plain VTK builds need not provide it.)
vtk_module_find_package(PRIVATE
  PACKAGE     Eigen3
  VERSION     3.3
  CONFIG_MODE)
vtk_module_link(ASM::Filters
  PRIVATE
    "$<BUILD_INTERFACE:Eigen3::Eigen>")

# Export only what is marked VTKASMFILTERS_EXPORT, as on Windows, so that a
# missing export shows up on Linux too (VTK itself builds this way).
vtk_module_set_properties(ASM::Filters
  CXX_VISIBILITY_PRESET     hidden
  VISIBILITY_INLINES_HIDDEN ON)
