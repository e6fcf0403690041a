// SPDX-License-Identifier: BSD-3-Clause
#include "vtkASMDistributed.h"

#include "Core/Budget.h"
#include "Core/CellSize.h"
#include "Core/CellFrame.h"

#include "vtkCommunicator.h"
#include "vtkDataArray.h"
#include "vtkDataSetAttributes.h"
#include "vtkMultiProcessController.h"
#include "vtkMultiProcessStream.h"
#include "vtkPointData.h"
#include "vtkPointSet.h"
#include "vtkUnsignedCharArray.h"

#include <algorithm>
#include <cstdlib>
#include <cstring>
#include <limits>
#include <numeric>
#include <utility>

namespace asmvtk
{
bool LaunchedByMPIRunner()
{
  // Set for every process by Open MPI's mpiexec and by MPICH's and Intel
  // MPI's Hydra launcher; absent in a desktop session and in a singleton
  // (an MPI program started on its own, e.g. the paraview GUI, which Open MPI
  // gives PMIX_* variables but no OMPI_COMM_WORLD_SIZE).
  for (const char* name : { "OMPI_COMM_WORLD_SIZE", "PMI_SIZE" })
  {
    const char* value = std::getenv(name);
    if (value && *value)
    {
      return true;
    }
  }
  return false;
}

bool IsDistributed(vtkMultiProcessController* controller, bool always)
{
  return controller != nullptr &&
    (controller->GetNumberOfProcesses() > 1 || always || LaunchedByMPIRunner());
}

//------------------------------------------------------------------------------
Communication::Communication(vtkMultiProcessController* controller)
  : Ctrl(controller)
{
  if (controller)
  {
    this->LocalRank = controller->GetLocalProcessId();
    this->Processes = std::max(1, controller->GetNumberOfProcesses());
  }
}

Index Communication::Sum(Index value) const
{
  long long in = value, out = value;
  if (this->Processes > 1)
  {
    this->Ctrl->AllReduce(&in, &out, 1, vtkCommunicator::SUM_OP);
  }
  return static_cast<Index>(out);
}

double Communication::Sum(double value) const
{
  double out = value;
  if (this->Processes > 1)
  {
    this->Ctrl->AllReduce(&value, &out, 1, vtkCommunicator::SUM_OP);
  }
  return out;
}

double Communication::Max(double value) const
{
  double out = value;
  if (this->Processes > 1)
  {
    this->Ctrl->AllReduce(&value, &out, 1, vtkCommunicator::MAX_OP);
  }
  return out;
}

void Communication::Sum(std::vector<double>& values) const
{
  if (this->Processes > 1 && !values.empty())
  {
    const std::vector<double> in = values;
    this->Ctrl->AllReduce(in.data(), values.data(), static_cast<vtkIdType>(in.size()),
      vtkCommunicator::SUM_OP);
  }
}

void Communication::Sum(std::vector<long long>& values) const
{
  if (this->Processes > 1 && !values.empty())
  {
    const std::vector<long long> in = values;
    this->Ctrl->AllReduce(in.data(), values.data(), static_cast<vtkIdType>(in.size()),
      vtkCommunicator::SUM_OP);
  }
}

asmcore::Bounds Communication::Union(const asmcore::Bounds& local) const
{
  // min(x), min(-x): one MIN reduction.
  const double inf = std::numeric_limits<double>::infinity();
  double in[6], out[6];
  for (int a = 0; a < 3; ++a)
  {
    in[a] = local.Valid ? local.Min[a] : inf;
    in[3 + a] = local.Valid ? -local.Max[a] : inf;
  }
  std::copy(in, in + 6, out);
  if (this->Processes > 1)
  {
    this->Ctrl->AllReduce(in, out, 6, vtkCommunicator::MIN_OP);
  }
  asmcore::Bounds b;
  b.Valid = out[0] <= -out[3];
  for (int a = 0; a < 3 && b.Valid; ++a)
  {
    b.Min[a] = out[a];
    b.Max[a] = -out[3 + a];
  }
  return b;
}

namespace
{
// All-to-all personalised exchange as K GatherV collectives (vtkCommunicator
// has no AllToAllV; collectives cannot deadlock whatever the message sizes).
template <typename T>
std::vector<T> ExchangeImpl(vtkMultiProcessController* ctrl, int rank, int size,
  std::vector<std::vector<T>>& send)
{
  if (size == 1)
  {
    return std::move(send[0]);
  }
  std::vector<long long> lengths(static_cast<std::size_t>(size));
  for (int r = 0; r < size; ++r)
  {
    lengths[r] = static_cast<long long>(send[r].size());
  }
  std::vector<long long> matrix(static_cast<std::size_t>(size) * size); // [from][to]
  ctrl->AllGather(lengths.data(), matrix.data(), size);
  std::vector<vtkIdType> recvLengths(static_cast<std::size_t>(size));
  std::vector<vtkIdType> offsets(static_cast<std::size_t>(size));
  vtkIdType total = 0;
  for (int from = 0; from < size; ++from)
  {
    recvLengths[from] = static_cast<vtkIdType>(matrix[from * size + rank]);
    offsets[from] = total;
    total += recvLengths[from];
  }
  std::vector<T> received(static_cast<std::size_t>(std::max<vtkIdType>(total, 1)));
  T dummy{};
  for (int root = 0; root < size; ++root)
  {
    const T* data = send[root].empty() ? &dummy : send[root].data();
    ctrl->GatherV(data, received.data(), static_cast<vtkIdType>(send[root].size()),
      recvLengths.data(), offsets.data(), root);
  }
  received.resize(static_cast<std::size_t>(total));
  send.clear();
  return received;
}

std::uint64_t Mix(std::uint64_t key)
{
  asmcore::SplitMix64 mix(key);
  return mix.Next();
}
} // namespace

std::vector<double> Communication::Exchange(std::vector<std::vector<double>>& send) const
{
  return ExchangeImpl(this->Ctrl, this->LocalRank, this->Processes, send);
}

std::vector<long long> Communication::Exchange(
  std::vector<std::vector<long long>>& send) const
{
  return ExchangeImpl(this->Ctrl, this->LocalRank, this->Processes, send);
}

std::vector<double> Communication::AllGather(const std::vector<double>& local, Index* offset) const
{
  if (offset)
  {
    *offset = 0;
  }
  if (this->Processes == 1)
  {
    return local;
  }
  long long n = static_cast<long long>(local.size());
  std::vector<long long> counts(static_cast<std::size_t>(this->Processes));
  this->Ctrl->AllGather(&n, counts.data(), 1);
  std::vector<vtkIdType> lengths(counts.begin(), counts.end());
  std::vector<vtkIdType> offsets(lengths.size(), 0);
  for (std::size_t r = 1; r < lengths.size(); ++r)
  {
    offsets[r] = offsets[r - 1] + lengths[r - 1];
  }
  const vtkIdType total = offsets.back() + lengths.back();
  if (offset)
  {
    *offset = static_cast<Index>(offsets[this->LocalRank]);
  }
  std::vector<double> all(static_cast<std::size_t>(std::max<vtkIdType>(total, 1)));
  double dummy = 0.0;
  this->Ctrl->AllGatherV(local.empty() ? &dummy : local.data(), all.data(),
    static_cast<vtkIdType>(local.size()), lengths.data(), offsets.data());
  all.resize(static_cast<std::size_t>(total));
  return all;
}

//------------------------------------------------------------------------------
Index CountOccupiedCells(const Communication& comm, const double* xyz,
  const std::vector<Index>& ids, const asmcore::GridSpec& spec)
{
  std::vector<std::uint64_t> keys(ids.size());
  for (std::size_t i = 0; i < ids.size(); ++i)
  {
    keys[i] = spec.KeyOf(xyz + 3 * ids[i]);
  }
  std::sort(keys.begin(), keys.end());
  keys.erase(std::unique(keys.begin(), keys.end()), keys.end());
  if (comm.Size() == 1)
  {
    return static_cast<Index>(keys.size());
  }
  // Each key is counted by one process, chosen by a hash of the key.
  std::vector<std::vector<long long>> send(static_cast<std::size_t>(comm.Size()));
  for (std::uint64_t key : keys)
  {
    send[Mix(key) % static_cast<std::uint64_t>(comm.Size())].push_back(static_cast<long long>(key));
  }
  std::vector<long long> mine = comm.Exchange(send);
  std::sort(mine.begin(), mine.end());
  const Index distinct = static_cast<Index>(std::unique(mine.begin(), mine.end()) - mine.begin());
  return comm.Sum(distinct);
}

//------------------------------------------------------------------------------
std::int64_t SlabPartition::AxisIndex(const double p[3]) const
{
  std::int64_t ijk[3];
  this->Grid.Unpack(this->Grid.KeyOf(p), ijk);
  return ijk[this->Axis];
}

int SlabPartition::OwnerOf(std::int64_t axisIndex) const
{
  const std::int64_t dim = this->Grid.Dims[this->Axis];
  axisIndex = std::min(std::max<std::int64_t>(axisIndex, 0), dim - 1);
  const auto bins = static_cast<std::int64_t>(this->BinOwner.size());
  return this->BinOwner[static_cast<std::size_t>(axisIndex * bins / dim)];
}

SlabPartition MakeSlabPartition(const Communication& comm, const asmcore::GridSpec& grid,
  const double* xyz, const std::vector<Index>& ids)
{
  SlabPartition slabs;
  slabs.Grid = grid;
  for (int a = 1; a < 3; ++a)
  {
    if (grid.Dims[a] > grid.Dims[slabs.Axis])
    {
      slabs.Axis = a;
    }
  }
  const std::int64_t dim = grid.Dims[slabs.Axis];
  const std::int64_t bins = std::min<std::int64_t>(dim, 1 << 16);
  std::vector<long long> histogram(static_cast<std::size_t>(bins), 0);
  slabs.BinOwner.assign(static_cast<std::size_t>(bins), 0);
  for (Index id : ids)
  {
    ++histogram[static_cast<std::size_t>(slabs.AxisIndex(xyz + 3 * id) * bins / dim)];
  }
  comm.Sum(histogram);
  const long long total = std::accumulate(histogram.begin(), histogram.end(), 0LL);
  long long before = 0;
  for (std::int64_t b = 0; b < bins && total > 0; ++b)
  {
    // The bin goes to the slab holding its middle point: contiguous slabs of
    // about total / K points each.
    const long double middle = before + 0.5L * histogram[b];
    slabs.BinOwner[b] = static_cast<int>(
      std::min<long double>(comm.Size() - 1, middle * comm.Size() / total));
    before += histogram[b];
  }
  return slabs;
}

//------------------------------------------------------------------------------
std::vector<Index> WithoutDuplicateGhosts(vtkPointSet* input, const std::vector<Index>& ids)
{
  auto* ghosts = vtkUnsignedCharArray::SafeDownCast(
    input->GetPointData()->GetArray(vtkDataSetAttributes::GhostArrayName()));
  if (!ghosts)
  {
    return ids;
  }
  std::vector<Index> kept;
  kept.reserve(ids.size());
  for (Index id : ids)
  {
    if (!(ghosts->GetValue(id) & vtkDataSetAttributes::DUPLICATEPOINT))
    {
      kept.push_back(id);
    }
  }
  return kept;
}

//------------------------------------------------------------------------------
namespace
{
// One transferred array: name, VTK type, components, attribute roles, and
// its place in a point's record (in doubles).
struct ArraySlot
{
  std::string Name;
  int Type = VTK_DOUBLE;
  int Components = 1;
  int Attributes = 0; // bit a: the array is attribute a
  int Offset = 0;
  int Width = 0;
};

bool Transferable(vtkAbstractArray* array)
{
  auto* data = vtkDataArray::SafeDownCast(array);
  return data && array->GetName() && data->GetDataType() != VTK_BIT &&
    std::strcmp(array->GetName(), vtkDataSetAttributes::GhostArrayName()) != 0;
}

// The arrays every process holding points can send, in the order of the
// first such process; names of the others in `dropped`.
std::vector<ArraySlot> AgreeOnArrays(const Communication& comm, vtkPointData* pd, bool hasPoints,
  std::vector<std::string>& dropped)
{
  vtkMultiProcessStream stream;
  std::vector<ArraySlot> slots;
  if (hasPoints)
  {
    for (int i = 0; i < pd->GetNumberOfArrays(); ++i)
    {
      vtkAbstractArray* array = pd->GetAbstractArray(i);
      if (!Transferable(array))
      {
        if (array->GetName() &&
          std::strcmp(array->GetName(), vtkDataSetAttributes::GhostArrayName()) != 0)
        {
          dropped.push_back(std::string(array->GetName()) + " (not a numeric array)");
        }
        continue;
      }
      ArraySlot slot;
      slot.Name = array->GetName();
      slot.Type = array->GetDataType();
      slot.Components = array->GetNumberOfComponents();
      for (int a = 0; a < vtkDataSetAttributes::NUM_ATTRIBUTES; ++a)
      {
        if (pd->GetAbstractAttribute(a) == array)
        {
          slot.Attributes |= 1 << a;
        }
      }
      slots.push_back(slot);
    }
  }
  if (comm.Size() == 1)
  {
    return slots;
  }
  // The first process with points decides the layout.
  std::vector<long long> has(static_cast<std::size_t>(comm.Size()), 0);
  has[comm.Rank()] = hasPoints ? 1 : 0;
  comm.Sum(has);
  const auto first = std::find(has.begin(), has.end(), 1LL);
  const int root = first == has.end() ? 0 : static_cast<int>(first - has.begin());
  if (comm.Rank() == root)
  {
    stream << static_cast<int>(slots.size());
    for (const ArraySlot& s : slots)
    {
      stream << s.Name << s.Type << s.Components << s.Attributes;
    }
  }
  comm.Controller()->Broadcast(stream, root);
  int count = 0;
  stream >> count;
  std::vector<ArraySlot> agreed(static_cast<std::size_t>(count));
  std::vector<long long> present(static_cast<std::size_t>(count), 1);
  for (int i = 0; i < count; ++i)
  {
    ArraySlot& s = agreed[i];
    stream >> s.Name >> s.Type >> s.Components >> s.Attributes;
    vtkDataArray* mine = hasPoints ? pd->GetArray(s.Name.c_str()) : nullptr;
    if (hasPoints &&
      (!mine || mine->GetDataType() != s.Type || mine->GetNumberOfComponents() != s.Components))
    {
      present[i] = 0;
    }
  }
  std::vector<long long> votes = present;
  comm.Sum(votes); // an array must be on every process with points
  const long long holders = std::accumulate(has.begin(), has.end(), 0LL);
  std::vector<ArraySlot> kept;
  for (int i = 0; i < count; ++i)
  {
    if (votes[i] == holders)
    {
      kept.push_back(agreed[i]);
    }
    else
    {
      dropped.push_back(agreed[i].Name + " (missing or different on some processes)");
    }
  }
  return kept;
}
} // namespace

LocalCloud Redistribute(const Communication& comm, vtkPointSet* input, const double* xyz,
  const std::vector<Index>& ids, const SlabPartition& partition, int haloRings)
{
  LocalCloud cloud;
  vtkPointData* inPD = input->GetPointData();
  std::vector<ArraySlot> slots = AgreeOnArrays(comm, inPD, !ids.empty(), cloud.Dropped);
  // Record: x y z | arrays (bytes, each padded to whole doubles) | rank id.
  int width = 3;
  for (ArraySlot& s : slots)
  {
    s.Offset = width;
    const int bytes = s.Components * vtkDataArray::GetDataTypeSize(s.Type);
    s.Width = (bytes + 7) / 8;
    width += s.Width;
  }
  const int payloadEnd = width;
  width += 2;

  std::vector<vtkDataArray*> arrays;
  for (const ArraySlot& s : slots)
  {
    arrays.push_back(inPD->GetArray(s.Name.c_str()));
  }
  std::vector<std::vector<double>> send(static_cast<std::size_t>(comm.Size()));
  std::vector<double> record(static_cast<std::size_t>(width));
  std::vector<int> destinations;
  std::vector<double> tuple;
  for (Index id : ids)
  {
    const double* p = xyz + 3 * id;
    std::fill(record.begin(), record.end(), 0.0);
    std::copy(p, p + 3, record.begin());
    for (std::size_t k = 0; k < slots.size(); ++k)
    {
      const ArraySlot& s = slots[k];
      auto* bytes = reinterpret_cast<unsigned char*>(record.data() + s.Offset);
      const int size = vtkDataArray::GetDataTypeSize(s.Type);
      if (arrays[k]->HasStandardMemoryLayout())
      {
        // The values' bytes, exactly.
        std::memcpy(bytes, arrays[k]->GetVoidPointer(id * s.Components),
          static_cast<std::size_t>(size * s.Components));
        continue;
      }
      tuple.resize(static_cast<std::size_t>(s.Components));
      arrays[k]->GetTuple(id, tuple.data());
      for (int c = 0; c < s.Components; ++c)
      {
        switch (s.Type)
        {
          vtkTemplateMacro(VTK_TT v = static_cast<VTK_TT>(tuple[c]);
                           std::memcpy(bytes + c * size, &v, sizeof(v)));
        }
      }
    }
    record[payloadEnd] = comm.Rank();
    record[payloadEnd + 1] = static_cast<double>(id);
    const std::int64_t axis = partition.AxisIndex(p);
    destinations.clear();
    for (int d = -haloRings; d <= haloRings; ++d)
    {
      destinations.push_back(partition.OwnerOf(axis + d));
    }
    std::sort(destinations.begin(), destinations.end());
    destinations.erase(std::unique(destinations.begin(), destinations.end()), destinations.end());
    for (int r : destinations)
    {
      send[r].insert(send[r].end(), record.begin(), record.end());
    }
  }
  const std::vector<double> received = comm.Exchange(send);

  // Canonical order: cell key, coordinates, then the record's bytes. Sorted
  // as compact items (no indirection unless two points coincide).
  struct Item
  {
    std::uint64_t Key;
    double P[3];
    std::size_t Record;
  };
  const std::size_t n = received.size() / static_cast<std::size_t>(width);
  std::vector<Item> items(n);
  for (std::size_t i = 0; i < n; ++i)
  {
    const double* r = received.data() + i * width;
    items[i] = { partition.Grid.KeyOf(r), { r[0], r[1], r[2] }, i };
  }
  std::sort(items.begin(), items.end(), [&](const Item& a, const Item& b) {
    if (a.Key != b.Key)
    {
      return a.Key < b.Key;
    }
    for (int c = 0; c < 3; ++c)
    {
      if (a.P[c] != b.P[c])
      {
        return a.P[c] < b.P[c];
      }
    }
    return std::memcmp(received.data() + a.Record * width + 3,
             received.data() + b.Record * width + 3, sizeof(double) * (payloadEnd - 3)) < 0;
  });
  std::vector<std::uint64_t> keys(n);
  std::vector<std::size_t> order(n);
  for (std::size_t i = 0; i < n; ++i)
  {
    keys[items[i].Record] = items[i].Key;
    order[i] = items[i].Record;
  }
  items.clear();
  items.shrink_to_fit();

  cloud.Xyz.resize(3 * n);
  cloud.Ids.resize(n);
  cloud.Keys.resize(n);
  cloud.Owned.resize(n);
  cloud.SourceRank.resize(n);
  cloud.SourceId.resize(n);
  cloud.PointData = vtkSmartPointer<vtkPointData>::New();
  std::vector<vtkSmartPointer<vtkDataArray>> outArrays;
  for (const ArraySlot& s : slots)
  {
    auto array = vtk::TakeSmartPointer(vtkDataArray::CreateDataArray(s.Type));
    array->SetName(s.Name.c_str());
    array->SetNumberOfComponents(s.Components);
    array->SetNumberOfTuples(static_cast<vtkIdType>(n));
    const int index = cloud.PointData->AddArray(array);
    for (int a = 0; a < vtkDataSetAttributes::NUM_ATTRIBUTES; ++a)
    {
      if (s.Attributes & (1 << a))
      {
        cloud.PointData->SetActiveAttribute(index, a);
      }
    }
    outArrays.push_back(array);
  }
  for (std::size_t i = 0; i < n; ++i)
  {
    const double* r = received.data() + order[i] * width;
    std::copy(r, r + 3, cloud.Xyz.begin() + 3 * i);
    cloud.Ids[i] = static_cast<Index>(i);
    cloud.Keys[i] = keys[order[i]];
    std::int64_t ijk[3];
    partition.Grid.Unpack(cloud.Keys[i], ijk);
    cloud.Owned[i] = partition.OwnerOf(ijk[partition.Axis]) == comm.Rank() ? 1 : 0;
    cloud.SourceRank[i] = static_cast<long long>(r[payloadEnd]);
    cloud.SourceId[i] = static_cast<long long>(r[payloadEnd + 1]);
    for (std::size_t k = 0; k < slots.size(); ++k)
    {
      const ArraySlot& s = slots[k];
      const std::size_t bytes =
        static_cast<std::size_t>(s.Components * vtkDataArray::GetDataTypeSize(s.Type));
      std::memcpy(outArrays[k]->GetVoidPointer(static_cast<vtkIdType>(i) * s.Components),
        r + s.Offset, bytes);
    }
  }
  return cloud;
}

//------------------------------------------------------------------------------
std::vector<Index> GlobalBudgets(const Communication& comm, const std::vector<std::uint64_t>& keys,
  const std::vector<Index>& capacity, const std::vector<double>& variation,
  const asmcore::SimplifyParameters& parameters, Index target)
{
  if (comm.Size() == 1)
  {
    return ApportionCells(capacity, variation, parameters, target);
  }
  // Cells travel as (key / 2^32, key % 2^32, count, variation) as doubles:
  // each part is exact (keys reach 2^63, beyond a double's 2^53).
  constexpr int W = 4;
  std::vector<double> mine;
  mine.reserve(W * keys.size());
  for (std::size_t c = 0; c < keys.size(); ++c)
  {
    mine.insert(mine.end(), { static_cast<double>(keys[c] >> 32),
                              static_cast<double>(keys[c] & 0xFFFFFFFFULL),
                              static_cast<double>(capacity[c]), variation[c] });
  }
  long long n = static_cast<long long>(mine.size());
  std::vector<long long> counts(static_cast<std::size_t>(comm.Size()));
  comm.Controller()->AllGather(&n, counts.data(), 1);
  std::vector<vtkIdType> lengths(counts.begin(), counts.end());
  std::vector<vtkIdType> offsets(lengths.size(), 0);
  for (std::size_t r = 1; r < lengths.size(); ++r)
  {
    offsets[r] = offsets[r - 1] + lengths[r - 1];
  }
  const vtkIdType total = offsets.back() + lengths.back();
  std::vector<double> all(static_cast<std::size_t>(comm.Rank() == 0 ? std::max<vtkIdType>(total, 1) : 1));
  double dummy = 0.0;
  comm.Controller()->GatherV(mine.empty() ? &dummy : mine.data(), all.data(),
    static_cast<vtkIdType>(mine.size()), lengths.data(), offsets.data(), 0);

  // Process 0: every cell, in key order, as the serial code sees them.
  std::vector<double> budgets(static_cast<std::size_t>(comm.Rank() == 0 ? std::max<vtkIdType>(total / W, 1) : 1));
  if (comm.Rank() == 0)
  {
    const std::size_t cells = static_cast<std::size_t>(total / W);
    std::vector<std::size_t> order(cells);
    std::iota(order.begin(), order.end(), std::size_t(0));
    std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
      return all[W * a] < all[W * b] || (all[W * a] == all[W * b] && all[W * a + 1] < all[W * b + 1]);
    });
    std::vector<Index> cap(cells);
    std::vector<double> var(cells);
    for (std::size_t i = 0; i < cells; ++i)
    {
      cap[i] = static_cast<Index>(all[W * order[i] + 2]);
      var[i] = all[W * order[i] + 3];
    }
    const std::vector<Index> sorted = ApportionCells(cap, var, parameters, target);
    for (std::size_t i = 0; i < cells; ++i)
    {
      budgets[order[i]] = static_cast<double>(sorted[i]); // back in gathered order
    }
  }
  std::vector<vtkIdType> cellLengths(lengths.size()), cellOffsets(lengths.size());
  for (std::size_t r = 0; r < lengths.size(); ++r)
  {
    cellLengths[r] = lengths[r] / W;
    cellOffsets[r] = offsets[r] / W;
  }
  std::vector<double> back(std::max<std::size_t>(keys.size(), 1));
  comm.Controller()->ScatterV(budgets.data(), back.data(), cellLengths.data(), cellOffsets.data(),
    static_cast<vtkIdType>(keys.size()), 0);
  std::vector<Index> result(keys.size());
  for (std::size_t c = 0; c < keys.size(); ++c)
  {
    result[c] = static_cast<Index>(back[c]);
  }
  return result;
}

//------------------------------------------------------------------------------
Index SimplifyShare::BudgetOf(std::uint64_t key) const
{
  const auto it = std::lower_bound(this->OwnedKeys.begin(), this->OwnedKeys.end(), key);
  return (it != this->OwnedKeys.end() && *it == key)
    ? this->Budgets[static_cast<std::size_t>(it - this->OwnedKeys.begin())]
    : -1; // a halo cell
}

SimplifyShare PrepareSimplify(const Communication& comm, vtkPointSet* input, const double* xyz,
  const std::vector<Index>& ids, const asmcore::SimplifyParameters& parameters)
{
  SimplifyShare share;
  const Index total = comm.Sum(static_cast<Index>(ids.size()));
  const asmcore::Bounds bounds = comm.Union(asmcore::ComputeBounds(xyz, ids));
  share.Diagonal = bounds.Diagonal();
  std::vector<double> centroid(3, 0.0);
  for (Index id : ids)
  {
    for (int a = 0; a < 3; ++a)
    {
      centroid[a] += xyz[3 * id + a];
    }
  }
  comm.Sum(centroid);
  for (int a = 0; a < 3; ++a)
  {
    share.Centroid[a] = total > 0 ? centroid[a] / static_cast<double>(total) : 0.0;
  }

  // 1. One global grid; the automatic size counts distinct cells globally.
  double cellSize = parameters.CellSize;
  if (!(cellSize > 0.0) || !std::isfinite(cellSize))
  {
    const double targetCells = static_cast<double>(std::min(parameters.NumberOfSamples, total)) /
      asmcore::SamplesPerCellOf(parameters);
    // As the serial search: first on the subsample picked by coordinates
    // (the same points however the cloud is split), then on all points.
    const std::vector<double> subset = asmcore::CellSizeSubsample(
      xyz, ids, static_cast<double>(total), targetCells);
    double start = 0.0;
    if (comm.Sum(static_cast<Index>(subset.size())) > 0)
    {
      std::vector<Index> subsetIds(subset.size() / 3);
      std::iota(subsetIds.begin(), subsetIds.end(), Index(0));
      start = asmcore::AutomaticCellSize(bounds, targetCells, total == 0,
        [&](const asmcore::GridSpec& spec) {
          return static_cast<double>(CountOccupiedCells(comm, subset.data(), subsetIds, spec));
        });
    }
    cellSize = asmcore::AutomaticCellSize(bounds, targetCells, total == 0,
      [&](const asmcore::GridSpec& spec) {
        return static_cast<double>(CountOccupiedCells(comm, xyz, ids, spec));
      },
      start);
  }
  share.Grid = asmcore::GridSpec::Make(bounds, cellSize);

  // 2. Owners, redistribution with the halo, canonical order.
  const SlabPartition slabs = MakeSlabPartition(comm, share.Grid, xyz, ids);
  share.Cloud = Redistribute(comm, input, xyz, ids, slabs, HaloRingsFor(parameters));

  // 3. The owned cells (consecutive runs of a key), and one global budget.
  const LocalCloud& cloud = share.Cloud;
  std::vector<Index> capacity;
  std::vector<double> variation;
  const std::size_t n = cloud.Ids.size();
  for (std::size_t i = 0; i < n;)
  {
    std::size_t j = i + 1;
    while (j < n && cloud.Keys[j] == cloud.Keys[i])
    {
      ++j;
    }
    if (cloud.Owned[i])
    {
      share.OwnedKeys.push_back(cloud.Keys[i]);
      capacity.push_back(static_cast<Index>(j - i));
      // The same frame the core computes (same points, same order).
      variation.push_back(asmcore::VariationWeightOf(parameters) != 0.0
          ? asmcore::ComputeCellFrame(cloud.Xyz.data(), cloud.Ids.data() + i, static_cast<Index>(j - i))
              .SurfaceVariation()
          : 0.0);
    }
    i = j;
  }
  share.Budgets = GlobalBudgets(comm, share.OwnedKeys, capacity, variation, parameters,
    std::min(parameters.NumberOfSamples, total));
  if (parameters.Mode == asmcore::SimplifyMode::FeaturePreserving)
  {
    ShareAllBudgets(comm, share); // halo cells need their true budgets
  }
  return share;
}
} // namespace asmvtk
