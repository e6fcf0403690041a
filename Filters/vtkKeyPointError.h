/**
 * @class   vtkKeyPointError
 * @brief   measure how well a simplified point cloud keeps an original one:
 *          the key point error of Yu & Wong (AKPE, MKPE) and the usual
 *          distances (Hausdorff, nearest neighbour, point to plane)
 *
 * Input port 0 is the original cloud, port 1 a simplified cloud (from
 * vtkASMSimplify or any other method: only the points are used). Both may be
 * any vtkPointSet, or a composite dataset of them, taken as one cloud as
 * vtkASMSimplify takes it; non-finite points are skipped with a warning.
 *
 * Key point error (paper §3.4): the key points of both clouds are found with
 * the paper's rule, that of vtkASMSimplify's PAPER mode (§3.2: per grid cell,
 * PCA, the Alpha bands along v2 clustered in the (v0, v1) plane, a key point
 * per cluster centroid; not the default mode's validated extremes) on one
 * grid covering both clouds, whose cell edge is CellSize, or, when that is
 * <= 0, vtkASMSimplify's automatic size for the simplified cloud's size at
 * SamplesPerCell samples per cell (the default 8: its PAPER mode's grid; 4:
 * its default mode's, FeatureSamplesPerCell). Each original key point is
 * paired with the nearest key point of the simplified cloud (its nearest
 * point when the simplified cloud has no key point). AKPE is the mean
 * (Eq. 1) and MKPE the maximum (Eq. 2) of the pair distances: Euclidean by
 * default, squared (the paper's Eq. 3 as printed) with DistanceMeasure =
 * SQUARED_DISTANCE. An original without key points (flat, or too sparse
 * for the grid's cells) has no key point error: AKPE and MKPE are NaN, with
 * a warning.
 *
 * The measures the field uses, so ASM can be compared with a voxel grid or
 * random sampling on equal terms: the symmetric Hausdorff distance between
 * the point sets; mean, RMS and maximum nearest-neighbour distance in each
 * direction; and the point-to-plane distance of every original point to the
 * simplified surface (a plane fitted to its PlaneNeighbors nearest simplified
 * points): mean, RMS, maximum. Neighbours that span no plane (exact
 * duplicates at one or two positions, or points on a line to 1e-6 of their
 * extent) give the distance to the nearest of them instead, as fewer than 3
 * neighbours do; so does "Error" below.
 *
 * Output port 0: the simplified cloud (one vertex per point) with every
 * input point array, "Error" (each simplified point's distance to the
 * original surface, a plane fitted to its PlaneNeighbors nearest original
 * points; NaN for skipped points), and, when GenerateCurvature is on,
 * "MeanCurvature" and "NeighborhoodSurfaceVariation" estimated from the
 * original cloud (NaN for skipped points; the mean curvature positive where
 * the surface bends away from the simplified cloud's normals, or, without
 * normals, away from the original cloud's centroid; normals with fewer
 * tuples than points are not used, with a warning); all figures as
 * one-value arrays in its field data, beside the simplified cloud's own
 * field data, whose arrays of the same names they replace: a
 * vtkASMSimplify output's AKPE, MKPE and CellSize (the simplifier's own
 * figures) give way to these, while its NumberOfKeyPoints (its key samples)
 * stays.
 * Output port 1: a one-row vtkTable of the same figures (ParaView shows it in
 * a spreadsheet view). In a distributed run (see SetController) the figures
 * are global, and only process 0's table has the row: the other processes
 * output the same columns with no row, as ParaView's global reductions
 * (vtkIntegrateAttributes) leave their satellites empty, so that the table
 * gathered over the processes (spreadsheet view, SaveData, Fetch) has one
 * row. The field data figures of port 0 stay on every process. Figure
 * names end in "Relative" when divided by the original's bounding-box
 * diagonal (by its square for squared AKPE/MKPE); NaN when that diagonal
 * is 0 (an original at one position).
 *
 * Points with NaN or infinite coordinates are skipped with a warning;
 * points flagged in vtkGhostType as another piece's (DUPLICATEPOINT) or
 * hidden (HIDDENPOINT) are skipped too, as vtkASMSimplify skips them
 * (skipped simplified points get NaN in "Error" and the curvature). A
 * cloud left with no point (empty, or every point skipped) gives a
 * warning and empty outputs, as in vtkASMSimplify. A cloud with coordinates beyond 1e100 in
 * magnitude, or all below 1e-100 (but not all 0), is an error with an empty output, as in
 * vtkASMSimplify.
 *
 * @sa vtkASMSimplify
 */

#ifndef vtkKeyPointError_h
#define vtkKeyPointError_h

#include "vtkASMFiltersModule.h" // For export macro
#include "vtkPolyDataAlgorithm.h"

class vtkAlgorithmOutput;
class vtkDataObject;
class vtkMultiProcessController;
class vtkTable;

class VTKASMFILTERS_EXPORT vtkKeyPointError : public vtkPolyDataAlgorithm
{
public:
  static vtkKeyPointError* New();
  vtkTypeMacro(vtkKeyPointError, vtkPolyDataAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  /// How paired key points are compared.
  enum DistanceMeasures
  {
    EUCLIDEAN_DISTANCE = 0, ///< |p - p'|, data units
    SQUARED_DISTANCE = 1    ///< |p - p'|^2 (paper Eq. 3 as printed), squared data units
  };

  ///@{
  /**
   * The simplified cloud, on input port 1 (port 0 is the original).
   */
  void SetSimplifiedConnection(vtkAlgorithmOutput* output) { this->SetInputConnection(1, output); }
  void SetSimplifiedData(vtkDataObject* data) { this->SetInputData(1, data); }
  ///@}

  /**
   * The figures table of output port 1 (GetOutput(1) is null there: it casts
   * to vtkPolyData, the type of port 0).
   */
  vtkTable* GetFiguresOutput();

  ///@{
  /**
   * Partition threshold of the key point rule, as in vtkASMSimplify's PAPER
   * mode (fraction of a cell's extent along v2, [0, 0.5]); default 1/8.
   */
  vtkSetClampMacro(Alpha, double, 0.0, 0.5);
  vtkGetMacro(Alpha, double);
  ///@}

  ///@{
  /**
   * Edge of the grid cells for the key points, in data units; <= 0 (default)
   * sizes it as vtkASMSimplify's automatic size does for the simplified
   * cloud's point count at SamplesPerCell samples per cell.
   */
  vtkSetMacro(CellSize, double);
  vtkGetMacro(CellSize, double);
  ///@}

  ///@{
  /**
   * Samples per non-empty cell assumed by the automatic cell size (points,
   * >= 1); default 8, vtkASMSimplify's SamplesPerCell, which gives its PAPER
   * mode's grid (4, its FeatureSamplesPerCell, gives its default mode's).
   */
  vtkSetClampMacro(SamplesPerCell, double, 1.0, VTK_DOUBLE_MAX);
  vtkGetMacro(SamplesPerCell, double);
  ///@}

  ///@{
  /**
   * Distance between paired key points: EUCLIDEAN_DISTANCE (default) or
   * SQUARED_DISTANCE (the paper's Eq. 3 read literally).
   */
  vtkSetClampMacro(DistanceMeasure, int, EUCLIDEAN_DISTANCE, SQUARED_DISTANCE);
  vtkGetMacro(DistanceMeasure, int);
  ///@}

  ///@{
  /**
   * Number of nearest points a local plane is fitted to for the
   * point-to-plane distances (points, >= 3); default 8.
   */
  vtkSetClampMacro(PlaneNeighbors, int, 3, 1000);
  vtkGetMacro(PlaneNeighbors, int);
  ///@}

  ///@{
  /**
   * When on (default), add "MeanCurvature" (1/length) and
   * "NeighborhoodSurfaceVariation" to the output, estimated at each
   * simplified point from its CurvatureNeighbors nearest original points.
   */
  vtkSetMacro(GenerateCurvature, bool);
  vtkGetMacro(GenerateCurvature, bool);
  vtkBooleanMacro(GenerateCurvature, bool);
  ///@}

  ///@{
  /**
   * Neighbourhood size of the curvature estimates (points, >= 6); default 20.
   */
  vtkSetClampMacro(CurvatureNeighbors, int, 6, 1000);
  vtkGetMacro(CurvatureNeighbors, int);
  ///@}

  ///@{
  /**
   * Original clouds with fewer points than this (per process) are compared
   * on the calling thread alone; larger ones run their loops through
   * vtkSMPTools. In points; 0: always through vtkSMPTools; default -1:
   * automatic, as vtkASMSimplify::MinimumPointsForThreads (50000 with the
   * STDThread backend, whose loops start their threads anew in VTK 9.1-9.2:
   * the 7.2 k-point fandisk took 0.019 s with 2 threads against 0.0085 with
   * 1; 0 with TBB and OpenMP). The figures are the same either way.
   */
  vtkSetClampMacro(MinimumPointsForThreads, vtkIdType, -1, VTK_ID_MAX);
  vtkGetMacro(MinimumPointsForThreads, vtkIdType);
  ///@}

  ///@{
  /**
   * The processes of a parallel run; default the global controller. With
   * several processes (pvbatch --mpi, pvserver) both clouds may be split
   * over them in any way: the figures are those of the whole clouds, the
   * same on every process in the field data of output 0 (see
   * vtkASMDistributedMetrics.h), and in the one row of process 0's table
   * (output 1; the other processes' tables have no row); each process
   * outputs its own simplified points.
   */
  virtual void SetController(vtkMultiProcessController*);
  vtkGetObjectMacro(Controller, vtkMultiProcessController);
  ///@}

protected:
  vtkKeyPointError();
  ~vtkKeyPointError() override;

  int FillInputPortInformation(int port, vtkInformation* info) override;
  int FillOutputPortInformation(int port, vtkInformation* info) override;
  int RequestData(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;

  double Alpha = 0.125;
  double CellSize = 0.0;
  double SamplesPerCell = 8.0;
  int DistanceMeasure = EUCLIDEAN_DISTANCE;
  int PlaneNeighbors = 8;
  bool GenerateCurvature = true;
  int CurvatureNeighbors = 20;
  vtkIdType MinimumPointsForThreads = -1;
  vtkMultiProcessController* Controller = nullptr;

private:
  vtkKeyPointError(const vtkKeyPointError&) = delete;
  void operator=(const vtkKeyPointError&) = delete;
};

#endif
