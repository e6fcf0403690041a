// SPDX-License-Identifier: BSD-3-Clause
/**
 * Private helpers of the ASM filters for distributed (MPI) runs, e.g.
 * `mpiexec -n K pvbatch --mpi`: the communication, written against
 * VTK::ParallelCore only (vtkMultiProcessController), so the module still
 * builds against a plain VTK without MPI. Not wrapped, not installed.
 *
 * Design (results do not depend on K or on how the input is split):
 *
 * 1. One global grid. The finite points' bounds are reduced over the
 *    processes; the automatic cell size runs the serial search
 *    (asmcore::AutomaticCellSize) with the number of DISTINCT non-empty cells
 *    over all processes (each process sends its cell keys to the process
 *    chosen by a hash of the key, which counts them once).
 * 2. One owner per cell. The grid is cut into K boxes of cells by recursive
 *    bisection (asmcore::CellPartition): a box of k processes is cut across
 *    its longest side where the points below make the share of k / 2 of
 *    them (a histogram along that side, reduced over the processes; one
 *    reduction per level of cuts). With K = 2 that is two slabs; with more,
 *    a process's halo grows with its box's surface, not with the whole
 *    cross-section of the cloud. Every point is sent to the owner of its cell, and
 *    to the processes owning a cell within HaloRingsFor(parameters) cells of
 *    it (halo points). Paper mode: HaloRings = 2 (neighbours only, no
 *    samples; used by the curvature estimates). Feature mode: see 7.
 *    Coordinates (as doubles) and every numeric point-data array travel in
 *    one record per point, with the sending process and point id.
 * 3. A canonical order. A process sorts the points it received by cell key,
 *    then coordinates, then array values, so a cell's points reach the core
 *    in the same order whatever the partition. The core then processes each
 *    cell's points in the cell's canonical order (asmcore::CanonicalOrder:
 *    a hash of the coordinates, then x, y, z, then id), a function of the
 *    points alone, as the serial path does with its points in input order;
 *    and the per-cell decisions are made on values (key points by
 *    prominence, Lloyd seeds by distance; Paper mode's random choice among
 *    key clusters draws them in the order of their extreme points'
 *    coordinates). So the serial path gives the same points as this one,
 *    even on gridded clouds whose points tie exactly everywhere (tests:
 *    the MPI lattice modes, DistributedFeatureHooks.*Lattice*). Among exact
 *    duplicates (the same position), the point a sample stands for is the
 *    one whose values come first (asmvtk::ChooseAmongDuplicates, after the
 *    core, on either path; here the string, variant and bit arrays, read
 *    after the run, decide among the copies that tie on the rest:
 *    FetchRepresentativeValues). (Key Point Error chooses among equidistant
 *    nearest samples by position too.) A one-process run started by mpiexec
 *    takes this path too (LaunchedByMPIRunner: ParaView built with MPI has
 *    a one-process MPI controller even in the built-in session, so the
 *    controller alone cannot tell "mpiexec -n 1" from a desktop session;
 *    the launcher's environment can), so K = 1, 2, 3 under mpiexec agree.
 *    A session not started by mpiexec takes the serial path unless
 *    AlwaysDistribute is on; the serial path gives the same points (7). The automatic cell size is
 * searched first on points picked by a hash of their coordinates (CellSizeSubsample), the same
 *    points for the serial and the distributed search.
 * 4. One global budget. The owners' (cell key, point count, surface
 *    variation) are gathered on process 0, which computes the shares and
 *    apportions N_s exactly as the serial code does (cells in key order) by
 *    the mode's rule (ApportionCells: Eq. 4 and largest remainder in Paper
 *    mode; n_c^BudgetExponent shares and ApportionWithCoverage with
 *    CoverEveryCell in the feature mode), and scatters the budgets back.
 * 5. Figures (AKPE, MKPE, counts) are sums and maxima reduced over the
 *    processes; per-cell seeds come from the cell key, as in serial runs.
 * 6. Curvature arrays are estimated by the owner of a sample's cell from the
 *    owned and halo points: exact while a sample's CurvatureNeighbors
 *    nearest input points lie within HaloRings cells (a cell holds about
 *    SamplesPerCell / fraction points, e.g. 160 at 5 %, so 20 neighbours
 *    are well inside; only with very few points per cell could a
 *    neighbourhood reach past the halo, and the estimate would then use the
 *    nearest points available).
 * 7. The feature-preserving mode (vtkASMDistributedFeature.cxx). A cell's
 *    samples and clusters depend on the points within
 *    asmcore::InfluenceRingsOf(parameters) rings of cells (key point
 *    validation across borders: 1; each CrossCellIterations Lloyd step: 2;
 *    each hole-filling round: 2; each FinalLloydIterations step: 4 when
 *    weighted by the variations of the clusters around (the first one 2
 *    after a cross-cell step or a hole-filling round, whose assignment it
 *    reuses), 2 otherwise; the final assignment: 2; 19 by default), given
 *    the grid, the budgets and the hole filling's moves. A halo that wide
 *    would be simplified redundantly by every neighbour, so instead the
 *    halo cells' samples are exchanged with their owners after every step
 *    that moves samples (the sampling inside the cells, each Lloyd step,
 *    each hole-filling or covering round: the core's ShareSamples hook,
 *    CollectiveChannel::ShareHook): then every step starts from exact
 *    samples in every cell this process holds, and the halo needs only the
 *    rings one step reads, asmcore::InfluenceRingsPerStep (4 with weighted
 *    final iterations, 2 otherwise), plus FeatureHaloMargin = 2 rings for
 *    the repair of empty clusters (FillEmptyClusters reads cluster sizes
 *    two rings away): 6 by default. Each exchange sends the samples of the
 *    cells within 6 rings of another process's box to that process. The
 *    weighted steps' mean variation
 *    is of the whole cloud: each process sums its owned samples' in fixed
 *    point (asmcore::ExactMean), and the sums are added over the processes
 *    (SumOverProcesses), so that the mean does not depend on the partition.
 *    The hole filling's moves are global (a sample moves from anywhere to
 *    the largest gaps of the whole cloud): each process ranks its owned
 *    cells' samples (the most crowded) and points (the farthest from every
 *    sample) and computes its candidates' removal costs; the rankings and
 *    costs are gathered (GatherOverProcesses), and every process runs the
 *    same greedy on them, so it makes the moves of a one-process run and
 *    applies them to the cells it holds (a sample may leave this process's
 *    cells or arrive from another's). A cost that moves made stale is
 *    computed again by its owner and gathered again (with up to 63 more
 *    stale ones), so the number of collectives depends on the data:
 *    CollectiveChannel lets a process whose run ended early take part in the
 *    others' collectives until every process is done.
 *    Every process learns every cell's budget (ShareAllBudgets), and the
 *    core simplifies the halo cells too with their TRUE budgets (hooks
 *    CellBudget = TrueBudgetOf, OutputCell = Owns): their samples are exact
 *    wherever an owned cell can see them, and only the owned cells' samples
 *    are output, with all their members (halo points included; points of
 *    owned cells that join a halo cell's sample are output by that cell's
 *    owner).
 *    BoundSnappedHoles, whose bound is the largest hole of the whole cloud,
 *    runs after the core, over all processes (BoundSnappedHolesAcross).
 *    Points that no sample
 *    within the searched rings takes (only when some cells get no sample)
 *    join the nearest sample this process holds, which may differ from the
 *    global nearest; an empty-cluster repair that chains over more than two
 *    rings could differ from a one-process run (not seen in the tests). A
 *    sample whose ring has nothing to give (N_s close to N) takes a point
 *    among those this process outputs (FillEmptyClusters' `output`): the
 *    halo's clusters are not exact far from the owned cells, so a point of
 *    the halo could otherwise be output twice, or an owned point taken by
 *    a halo sample that is empty here only, and lost.
 *
 * Numeric point-data arrays travel with the points, in their records;
 * string, variant and bit arrays are read after the run at the samples'
 * representatives (FetchRepresentativeValues: the value a serial run gives
 * them, exact duplicates included). An array that some process with points
 * lacks (or has with another type, fewer components or fewer tuples than
 * points) is dropped with a warning, as are unnamed arrays. Points flagged
 * as duplicate ghosts or hidden (vtkGhostType) are skipped.
 * The core runs unchanged on each process's points through hooks in
 * asmcore::SimplifyParameters (Grid, CellBudget, CloudCentroid, OutputCell);
 * halo cells are passed to it too (Paper: budget -1, neighbours only;
 * feature mode: true budgets, not output).
 */
#ifndef vtkASMDistributed_h
#define vtkASMDistributed_h

#include "Core/CellPartition.h"
#include "Core/Grid.h"
#include "Core/Simplify.h"

#include "vtkSmartPointer.h"

#include <functional>
#include <string>
#include <vector>

class vtkMultiProcessController;
class vtkPointData;
class vtkPointSet;

namespace asmvtk
{
using asmcore::Index;

/// Width of the halo, in grid cells, sent around the cells a process owns
/// (paper mode; see HaloRingsFor).
constexpr int HaloRings = 2;

/// Extra rings of the feature-preserving mode's halo beyond
/// asmcore::InfluenceRingsPerStep: the repair of empty clusters reads the
/// cluster sizes of samples two rings away (vtkASMDistributedFeature.cxx).
constexpr int FeatureHaloMargin = 2;

/// The halo width of a run: HaloRings in Paper mode; in the
/// feature-preserving mode InfluenceRingsPerStep(parameters) +
/// FeatureHaloMargin (at least HaloRings; 6 by default): the halo cells'
/// samples are exchanged with their owners after every step
/// (CollectiveChannel::ShareHook), so that every owned cell's samples and
/// clusters come out as in a one-process run.
int HaloRingsFor(const asmcore::SimplifyParameters& parameters);

/// Budgets of cells (in ascending key order) by the rule of the mode:
/// Eq. 4 shares and ApportionBudget (Paper), or shares w_c * n_c^gamma
/// (BudgetExponent) and ApportionWithCoverage (CoverEveryCell).
std::vector<Index> ApportionCells(const std::vector<Index>& capacity,
  const std::vector<double>& variation, const asmcore::SimplifyParameters& parameters,
  Index target);

/// True when this process was started by an MPI launcher (mpiexec/mpirun of
/// Open MPI, MPICH or Intel MPI): its environment says so
/// (OMPI_COMM_WORLD_SIZE, PMI_SIZE).
bool LaunchedByMPIRunner();

/// True when the run takes the distributed path: `controller` has several
/// processes, or one process started by an MPI launcher (`mpiexec -n 1
/// pvbatch --mpi`: it then gives the same answer as K processes), or
/// `always` and there is a controller. Otherwise (a desktop session, a
/// builtin ParaView session, plain VTK) the serial path, unchanged.
bool IsDistributed(vtkMultiProcessController* controller, bool always);

/// Collective operations of one run (every process must make the same calls
/// in the same order).
class Communication
{
public:
  explicit Communication(vtkMultiProcessController* controller);
  int Rank() const { return this->LocalRank; }
  int Size() const { return this->Processes; }

  Index Sum(Index value) const;
  double Sum(double value) const;
  double Max(double value) const;
  void Sum(std::vector<double>& values) const;
  void Sum(std::vector<long long>& values) const;
  /// Union of the processes' bounds (invalid ones ignored).
  asmcore::Bounds Union(const asmcore::Bounds& local) const;
  /// send[r] goes to process r; returns what every process sent to this
  /// one, concatenated in process order. Empties `send`. (PointArrays: the
  /// received values are not zero filled before they arrive.)
  asmcore::PointArray<double> Exchange(std::vector<asmcore::PointArray<double>>& send) const;
  asmcore::PointArray<long long> Exchange(std::vector<asmcore::PointArray<long long>>& send) const;
  /// Every process's `local`, concatenated in process order, on every process.
  /// `offset` (optional): where this process's values start in the result.
  std::vector<double> AllGather(const std::vector<double>& local, Index* offset = nullptr) const;
  vtkMultiProcessController* Controller() const { return this->Ctrl; }

private:
  vtkMultiProcessController* Ctrl;
  int LocalRank = 0;
  int Processes = 1;
};

/// Distinct non-empty cells of `spec` over all processes (collective).
Index CountOccupiedCells(const Communication& comm, const double* xyz, asmcore::IdView ids,
  const asmcore::GridSpec& spec, const asmcore::Execution& execution = {});

/// The non-empty cells of `spec` over all processes, each counted by its
/// share (asmcore::SparseCellShare of its points summed over the processes),
/// in fixed point: the serial EffectiveOccupiedCells' value (collective).
double EffectiveOccupiedCells(const Communication& comm, const double* xyz, asmcore::IdView ids,
  const asmcore::GridSpec& spec, double minPoints, const asmcore::Execution& execution = {});

/// The serial automatic cell size (asmcore::AutomaticCellSize: the search on
/// the coordinate-picked subsample, then on all points, then the sparse-cell
/// search), for the points of all processes (`total` of them, in `bounds`):
/// the same value as a serial run on the whole cloud (collective).
double AutomaticCellSize(const Communication& comm, const double* xyz, asmcore::IdView ids,
  const asmcore::Bounds& bounds, Index total, double targetCells,
  const asmcore::Execution& execution = {});

/// Collective: which process owns each cell of `grid` (boxes of cells from a
/// recursive bisection balanced by the points xyz[3*id], id in ids, of every
/// process; asmcore::MakeCellPartition).
asmcore::CellPartition MakeCellPartition(const Communication& comm, const asmcore::GridSpec& grid,
  const double* xyz, asmcore::IdView ids, const asmcore::Execution& execution = {});

/// A point-data array that does not travel with the points (a string,
/// variant or bit array): read at the samples' representatives after the
/// run (FetchRepresentativeValues).
struct FetchedArray
{
  std::string Name;
  int Type;
  int Components;
};

/// The points a process holds after redistribution, in canonical order.
struct LocalCloud
{
  /// (The per-point arrays are PointArrays: filled in parallel, no serial
  /// zero fill first.)
  asmcore::PointArray<double> Xyz; ///< owned and halo points
  /// Their cells, in slot order (point i in slot i): cell c holds the points
  /// [Cells.CellStart[c], Cells.CellStart[c + 1]), keys ascending.
  asmcore::CellGrid Cells;
  asmcore::PointArray<char> Owned;         ///< 1: in a cell this process owns
  asmcore::PointArray<int> SourceRank;     ///< process that held the point
  asmcore::PointArray<long long> SourceId; ///< its point id there

  Index Size() const { return static_cast<Index>(this->Xyz.size() / 3); }
  /// The points, 0 .. Size() - 1.
  asmcore::IdView Ids() const { return asmcore::IdView::Identity(this->Xyz.size() / 3); }
  vtkSmartPointer<vtkPointData> PointData; ///< the transferred arrays
  std::vector<FetchedArray> Fetched;       ///< arrays read after the run
  std::vector<std::string> ArrayOrder;     ///< every array passed on, in input order
  std::vector<std::string> Dropped;        ///< arrays not transferred (and why)
};

/// Collective: send every point (xyz[3*id], id in ids, with the numeric
/// point-data arrays of `input`) to the owner of its cell and, as a halo
/// point, to the owners of the cells within `haloRings` cells. String,
/// variant and bit arrays are listed in LocalCloud::Fetched instead. Arrays
/// that some process with points lacks, or has with fewer tuples than
/// points, are dropped (LocalCloud::Dropped says why). A process without
/// points (`ids` empty) need not have the arrays: it sends no values, and
/// the arrays' types and components come from the processes with points.
LocalCloud Redistribute(const Communication& comm, vtkPointSet* input, const double* xyz,
  asmcore::IdView ids, const asmcore::CellPartition& partition, int haloRings,
  const asmcore::Execution& execution = {});

/// Collective: the budgets N_c of this process's cells (`keys`, with
/// `capacity` points and surface variation `variation`), apportioned over
/// every process's cells on process 0 as asmcore::Simplify does (shares of
/// Eq. 4 in key order, ApportionBudget): they add up to `target` over all
/// processes (or to the number of points, when smaller).
std::vector<Index> GlobalBudgets(const Communication& comm, const std::vector<std::uint64_t>& keys,
  const std::vector<Index>& capacity, const std::vector<double>& variation,
  const asmcore::SimplifyParameters& parameters, Index target);

/// A process's share of a distributed vtkASMSimplify run.
struct SimplifyShare
{
  LocalCloud Cloud;                     ///< owned and halo points, canonical order
  asmcore::GridSpec Grid;               ///< the global grid
  std::vector<std::uint64_t> OwnedKeys; ///< the cells this process owns, ascending
  std::vector<Index> Budgets;           ///< their budgets (global apportionment)
  double Centroid[3] = { 0, 0, 0 };     ///< of the whole cloud
  double Diagonal = 0.0;                ///< of the whole cloud's bounding box
  asmcore::CellPartition Partition;     ///< who owns which cells
  /// Feature mode: every cell of every process, ascending, and its budget.
  std::vector<std::uint64_t> AllKeys;
  std::vector<Index> AllBudgets;

  /// Budget of a cell (-1 for cells owned elsewhere: halo cells).
  Index BudgetOf(std::uint64_t key) const;
  /// Feature mode: the budget of any cell, halo cells included (0 if unknown).
  Index TrueBudgetOf(std::uint64_t key) const;
  /// Whether this process owns the cell.
  bool Owns(std::uint64_t key) const;
};

/// Collective (feature mode): every process's owned cells and budgets into
/// share.AllKeys / AllBudgets on every process (a few numbers per cell).
void ShareAllBudgets(const Communication& comm, SimplifyShare& share);

/// Feature mode, BoundSnappedHoles (collective, after the core's run on every
/// process, which left the bound out): the bound of the whole cloud from
/// every process's samples (asmcore::SnappedHoles.h, in steps: the largest
/// reach of the samples that stay, reduced over the processes; every
/// process's candidates gathered and scanned widest first, ties by
/// position), then each process moves its own samples in `result` (whose
/// members are ids into `xyz`, as the core returned them). The result is
/// the serial run's except for candidates of exactly equal reach and
/// position.
void BoundSnappedHolesAcross(const Communication& comm, asmcore::Coordinates xyz,
  asmcore::SimplifyResult& result, const asmcore::Execution& execution);

/// Feature mode: the core's collective hooks over `comm`
/// (asmcore::SimplifyParameters: SumOverProcesses, GatherOverProcesses).
/// How many collectives a run makes depends on its data (the hole filling
/// gathers until its moves are decided), so a process whose run ended
/// early (no points of its own, a run cut short) cannot make them ahead:
/// every collective is a gather that carries whether its sender still runs,
/// and Finish() takes part in the others' remaining ones with nothing until
/// no process runs. Call Finish() after the core on every process.
class CollectiveChannel
{
public:
  explicit CollectiveChannel(const Communication& comm);
  std::function<void(std::vector<long long>&)> SumHook();
  std::function<void(std::vector<double>&)> GatherHook();
  /// The core's ShareSamples hook: each process sends the samples of its
  /// owned cells to the processes whose box lies within `rings` cells
  /// (their halo), and takes the ones it receives for its halo cells.
  std::function<void(
    const std::vector<std::uint64_t>&, const std::vector<Index>&, std::vector<double>&)>
  ShareHook(const SimplifyShare& share, int rings);
  void Finish();

private:
  enum Kind
  {
    Done = 0,
    Data = 1,     ///< a gather or a sum: the payloads
    Exchange = 2, ///< a personalised exchange follows (Communication::Exchange)
  };
  /// One collective: this process's kind and payload; returns the payloads
  /// of the processes that still run, in process order (and whether one of
  /// them asks for an exchange).
  std::vector<std::vector<double>> Round(
    Kind kind, const std::vector<double>& payload, bool* exchange = nullptr);
  const Communication& Comm;
};

/// Collective: global bounds and cell size (parameters.CellSize, or the
/// automatic one for parameters.NumberOfSamples and SamplesPerCell), boxes,
/// redistribution with a halo of HaloRingsFor(parameters) cells, and the
/// global budgets (feature mode: also every cell's, ShareAllBudgets).
SimplifyShare PrepareSimplify(const Communication& comm, vtkPointSet* input, const double* xyz,
  asmcore::IdView ids, const asmcore::SimplifyParameters& parameters,
  const asmcore::Execution& execution = {});

/// Points the core's run at this process's share: its grid and cells, the
/// budgets (paper mode: of the owned cells, halo cells left without
/// samples; feature mode: every cell's true budget, the halo cells as
/// context, only the owned cells output) and the whole cloud's centroid.
/// `share` must outlive the run.
void RunOnShare(const SimplifyShare& share, asmcore::SimplifyParameters& parameters);

/// Collective, after the core's run: the key point figures of the whole
/// cloud in `result` (sums and maxima over the processes), the grid's cell
/// size, and whether any process aborted.
void CombineFigures(
  const Communication& comm, const SimplifyShare& share, asmcore::SimplifyResult& result);

/// Collective, after the core's run: the arrays of `cloud.Fetched` for the
/// samples of `result`, each sample taking the value of its representative
/// (cloud.SourceRank, cloud.SourceId): each process asks the processes that
/// hold its samples' representatives, which read them from their input's
/// point data `inputPD` and send them back (an exact encoding: strings as
/// bytes, variants with their type, bits as bytes). `ties` (sample, point),
/// from ChooseAmongDuplicates: exact duplicates of a sample's
/// representative with the same values in every array that travelled;
/// their fetched values are asked for too, and the one whose values come
/// first (array by array in the input's order, CompareTuples; then the
/// representative) becomes the representative, as a serial run chooses.
/// The arrays go into `fetchedPD` (AddFetchedArrays puts them in the
/// output). Returns false (and adds nothing) when a reply could not be read.
bool FetchRepresentativeValues(const Communication& comm, vtkPointData* inputPD,
  const LocalCloud& cloud, const std::vector<std::pair<vtkIdType, asmcore::Index>>& ties,
  asmcore::SimplifyResult& result, vtkPointData* fetchedPD);

/// Adds the arrays of `fetchedPD` to `outPD`, which then holds its arrays in
/// the input's order (cloud.ArrayOrder), as on the serial path.
void AddFetchedArrays(vtkPointData* fetchedPD, const LocalCloud& cloud, vtkPointData* outPD);

/// The centroid of the points xyz[3 id], id in `ids`, over every process
/// (`total`: their number over the processes; 0 gives the origin). Each
/// process sums its own in id order, then the sums are added.
void GlobalCentroid(const Communication& comm, const double* xyz, asmcore::IdView ids, Index total,
  double centroid[3]);

/// Drops from `ids` the points flagged as duplicates of another process's
/// or piece's points, or as hidden (blanked: not part of the data), in
/// vtkGhostType (DUPLICATEPOINT, HIDDENPOINT): `ids` then views
/// `list`, which holds the others. Without a ghost array (or with one
/// shorter than the points) nothing changes (no copy).
void DropGhostPoints(vtkPointSet* input, asmcore::IdView& ids, asmcore::PointIds& list);
} // namespace asmvtk

#endif
