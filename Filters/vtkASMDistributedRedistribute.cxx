// SPDX-License-Identifier: BSD-3-Clause
// MPI runs: the points and their arrays sent to the processes that own
// their cells (Redistribute, vtkASMDistributed.h).
#include "vtkASMDistributed.h"

#include "Core/Grid.h"
#include "Core/Selection.h"

#include "vtkBitArray.h"
#include "vtkCommunicator.h"
#include "vtkDataArray.h"
#include "vtkDataSetAttributes.h"
#include "vtkMultiProcessController.h"
#include "vtkMultiProcessStream.h"
#include "vtkPointData.h"
#include "vtkPointSet.h"
#include "vtkStringArray.h"
#include "vtkVariantArray.h"

#include <algorithm>
#include <cstddef>
#include <cstring>
#include <numeric>
#include <utility>

namespace asmvtk
{
//------------------------------------------------------------------------------
namespace
{
// One array of a distributed run: name, VTK type, components, attribute
// roles; numeric arrays travel with the points, as bytes at Offset in each
// point's record (Width doubles); the others (Fetched) are read for the
// samples' representatives after the run (FetchRepresentativeValues).
struct ArraySlot
{
  std::string Name;
  int Type = VTK_DOUBLE;
  int Components = 1;
  int Attributes = 0; // bit a: the array is attribute a
  bool Fetched = false;
  int Offset = 0;
  int Width = 0;
};

// Whether `array` can be passed on in a distributed run, and how.
enum class Travel
{
  WithThePoints, // numeric arrays: their bytes in each point's record
  Fetched,       // strings, variants, bits: read at the representatives
  Not,
};
Travel HowItTravels(vtkAbstractArray* array)
{
  if (vtkDataArray::SafeDownCast(array) && array->GetDataType() != VTK_BIT)
  {
    return Travel::WithThePoints;
  }
  return vtkStringArray::SafeDownCast(array) || vtkVariantArray::SafeDownCast(array) ||
      vtkBitArray::SafeDownCast(array)
    ? Travel::Fetched
    : Travel::Not;
}

// The arrays every process holding points can pass on, in the order of the
// first such process; names of the others in `dropped` (with the reason).
// An array must have a tuple for each of the process's `points` points, as
// on the serial path.
std::vector<ArraySlot> AgreeOnArrays(const Communication& comm, vtkPointData* pd, Index points,
  bool hasPoints, std::vector<std::string>& dropped)
{
  vtkMultiProcessStream stream;
  std::vector<ArraySlot> slots;
  if (hasPoints)
  {
    for (int i = 0; i < pd->GetNumberOfArrays(); ++i)
    {
      vtkAbstractArray* array = pd->GetAbstractArray(i);
      if (!array->GetName())
      {
        dropped.emplace_back("(unnamed; the processes match arrays by name)");
        continue;
      }
      if (std::strcmp(array->GetName(), vtkDataSetAttributes::GhostArrayName()) == 0)
      {
        continue; // (the run's own input: duplicate points are skipped)
      }
      const Travel travel = HowItTravels(array);
      if (travel == Travel::Not || array->GetNumberOfTuples() < points ||
        array->GetNumberOfComponents() < 1)
      {
        dropped.push_back(std::string(array->GetName()) +
          (travel == Travel::Not ? " (an array type a distributed run cannot send)"
                                 : " (fewer tuples than points)"));
        continue;
      }
      ArraySlot slot;
      slot.Name = array->GetName();
      slot.Type = array->GetDataType();
      slot.Components = array->GetNumberOfComponents();
      slot.Fetched = travel == Travel::Fetched;
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
      stream << s.Name << s.Type << s.Components << s.Attributes << static_cast<int>(s.Fetched);
    }
  }
  comm.Controller()->Broadcast(stream, root);
  int count = 0;
  stream >> count;
  std::vector<ArraySlot> agreed(static_cast<std::size_t>(count));
  // (Votes of the processes with points only: a process without points has
  // no arrays, and must not count for or against one.)
  std::vector<long long> present(static_cast<std::size_t>(count), 0);
  for (int i = 0; i < count; ++i)
  {
    ArraySlot& s = agreed[i];
    int fetched = 0;
    stream >> s.Name >> s.Type >> s.Components >> s.Attributes >> fetched;
    s.Fetched = fetched != 0;
    const auto same = [&s](const ArraySlot& mine) {
      return mine.Name == s.Name && mine.Type == s.Type && mine.Components == s.Components;
    };
    present[i] = hasPoints && std::any_of(slots.begin(), slots.end(), same) ? 1 : 0;
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
  asmcore::IdView ids, const asmcore::CellPartition& partition, int haloRings,
  const asmcore::Execution& execution)
{
  LocalCloud cloud;
  vtkPointData* inPD = input->GetPointData();
  std::vector<ArraySlot> slots =
    AgreeOnArrays(comm, inPD, input->GetNumberOfPoints(), !ids.empty(), cloud.Dropped);
  // (Strings, variants and bits are read after the run, for the samples.)
  for (const ArraySlot& s : slots)
  {
    cloud.ArrayOrder.push_back(s.Name);
    if (s.Fetched)
    {
      cloud.Fetched.push_back({ s.Name, s.Type, s.Components });
    }
  }
  slots.erase(
    std::remove_if(slots.begin(), slots.end(), [](const ArraySlot& s) { return s.Fetched; }),
    slots.end());
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

  // Where this process reads each slot's values. Only a process that sends
  // points reads any: AgreeOnArrays kept an array only if every such process
  // has it with the agreed type and components. A process without points
  // voted for none, may lack the arrays (or hold others of the same name),
  // and sends no tuple: its records' layout comes from the agreement (the
  // slots) alone, and its entries stay null.
  std::vector<vtkDataArray*> arrays(slots.size(), nullptr);
  if (!ids.empty())
  {
    for (std::size_t a = 0; a < slots.size(); ++a)
    {
      arrays[a] = inPD->GetArray(slots[a].Name.c_str());
    }
  }
  // A point goes to the owners of the cells within haloRings of its own.
  const int processes = comm.Size();
  auto forEachDestination = [&](const double* p, auto&& visit) {
    std::int64_t ijk[3];
    partition.CellOfPoint(p, ijk);
    partition.ForEachOwnerNear(ijk, haloRings, visit);
  };
  // Each process's records are counted first, so that the buffers are
  // allocated once (not zero filled: each record is written whole, the
  // padding bytes of the arrays' slots zeroed).
  // Fixed blocks of the ids, each counting and then writing its own part
  // of every buffer: the buffers are the same whatever the thread count
  // (each destination's records in id order).
  const auto count = static_cast<Index>(ids.size());
  const Index blocks = asmcore::selection::BlockCount(count, Index(1) << 16);
  auto blockBegin = [&](Index b) { return asmcore::selection::BlockBegin(count, blocks, b); };
  const auto k = static_cast<std::size_t>(processes);
  std::vector<std::size_t> at(static_cast<std::size_t>(blocks) * k, 0); // per (block, process)
  execution.Run(0, blocks, [&](Index first, Index last) {
    for (Index b = first; b < last; ++b)
    {
      std::size_t* records = at.data() + static_cast<std::size_t>(b) * k;
      for (Index j = blockBegin(b); j < blockBegin(b + 1); ++j)
      {
        forEachDestination(xyz + 3 * ids[j], [&](int r) { ++records[r]; });
      }
    }
  });
  std::vector<asmcore::PointArray<double>> send(k);
  for (std::size_t r = 0; r < k; ++r)
  {
    std::size_t total = 0; // (from here on at[b][r]: where block b writes for r)
    for (Index b = 0; b < blocks; ++b)
    {
      const std::size_t n = at[static_cast<std::size_t>(b) * k + r];
      at[static_cast<std::size_t>(b) * k + r] = total;
      total += n;
    }
    send[r].resize(total * static_cast<std::size_t>(width));
  }
  // Non-standard memory layouts are read through GetTuple, on one thread.
  bool standard = true;
  for (vtkDataArray* array : arrays)
  {
    standard = standard && (!array || array->HasStandardMemoryLayout());
  }
  auto fill = [&](Index first, Index last) {
    std::vector<double> tuple;
    for (Index b = first; b < last; ++b)
    {
      std::size_t* records = at.data() + static_cast<std::size_t>(b) * k;
      for (Index j = blockBegin(b); j < blockBegin(b + 1); ++j)
      {
        const Index id = ids[j];
        const double* p = xyz + 3 * id;
        double* record = nullptr; // (written once, at the first destination, then copied)
        forEachDestination(p, [&](int r) {
          double* to = send[r].data() + records[r]++ * static_cast<std::size_t>(width);
          if (record)
          {
            std::copy(record, record + width, to);
            return;
          }
          record = to;
          for (int a = 0; a < 3; ++a)
          {
            record[a] = p[a];
          }
          std::fill(record + 3, record + payloadEnd, 0.0); // (records are compared byte for byte)
          for (std::size_t a = 0; a < slots.size(); ++a)
          {
            const ArraySlot& s = slots[a];
            auto* bytes = reinterpret_cast<unsigned char*>(record + s.Offset);
            const int size = vtkDataArray::GetDataTypeSize(s.Type);
            if (arrays[a]->HasStandardMemoryLayout())
            {
              // The values' bytes, exactly.
              std::memcpy(bytes, arrays[a]->GetVoidPointer(id * s.Components),
                static_cast<std::size_t>(size) * static_cast<std::size_t>(s.Components));
              continue;
            }
            tuple.resize(static_cast<std::size_t>(s.Components));
            arrays[a]->GetTuple(id, tuple.data());
            for (int c = 0; c < s.Components; ++c)
            {
              switch (s.Type)
              {
                vtkTemplateMacro(VTK_TT v = static_cast<VTK_TT>(tuple[c]); std::memcpy(
                  bytes + static_cast<std::ptrdiff_t>(c) * size, &v, sizeof(v)));
              }
            }
          }
          record[payloadEnd] = comm.Rank();
          record[payloadEnd + 1] = static_cast<double>(id);
        });
      }
    }
  };
  if (standard)
  {
    execution.Run(0, blocks, fill);
  }
  else
  {
    fill(0, blocks);
  }
  const asmcore::PointArray<double> received = comm.Exchange(send);

  // Canonical order: cell key, coordinates, then the record's bytes. The
  // points are grouped by cell as the core groups them (a counting sort of
  // their coordinates, cells in key order); then, cell by cell, the records
  // are gathered (scattered over the received ones: loaded ahead), sorted,
  // and copied out while they are in the cache.
  const std::size_t n = received.size() / static_cast<std::size_t>(width);
  cloud.Xyz.resize(3 * n);
  execution.Run(0, static_cast<Index>(n), [&](Index first, Index last) {
    for (auto i = static_cast<std::size_t>(first); i < static_cast<std::size_t>(last); ++i)
    {
      for (int a = 0; a < 3; ++a) // (not std::copy: a call to memmove per point)
      {
        cloud.Xyz[3 * i + a] = received[i * width + a];
      }
    }
  });
  const asmcore::CellGrid grid = asmcore::BuildCellGrid(
    cloud.Xyz.data(), asmcore::IdView::Identity(n), partition.Grid, execution);
  // (From here on cloud.Xyz is rewritten in canonical order.)
  cloud.Cells.Spec = grid.Spec;
  cloud.Cells.CellStart = grid.CellStart;
  cloud.Cells.CellKey = grid.CellKey;
  cloud.Cells.SlotOrder = true;
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
  // A cell's records are sorted by x as an unsigned integer (ordered as the
  // doubles, -0 as +0), then runs of equal x by y, z and the bytes.
  struct Item
  {
    std::uint64_t X;
    const double* Record;
  };
  auto orderedBits = [](double x) {
    x = x == 0.0 ? 0.0 : x; // (-0 == +0)
    std::uint64_t bits;
    std::memcpy(&bits, &x, sizeof(bits));
    return (bits >> 63) ? ~bits : bits | (std::uint64_t(1) << 63);
  };
  auto before = [payloadEnd](const Item& a, const Item& b) {
    for (int k = 1; k < 3; ++k)
    {
      if (a.Record[k] != b.Record[k])
      {
        return a.Record[k] < b.Record[k];
      }
    }
    return std::memcmp(a.Record + 3, b.Record + 3, sizeof(double) * (payloadEnd - 3)) < 0;
  };
  constexpr Index Ahead = 16;
  const auto last = static_cast<Index>(n);
  // (Cells in parallel: each writes its own points' slots.)
  execution.Run(0, grid.NumberOfCells(), [&](Index firstCell, Index lastCell) {
    std::vector<Item> items;
    for (Index c = firstCell; c < lastCell; ++c)
    {
      const Index first = grid.CellStart[c];
      items.clear();
      for (Index i = first; i < grid.CellStart[c + 1]; ++i)
      {
        if (i + Ahead < last)
        {
          asmcore::Prefetch(received.data() + grid.Order[i + Ahead] * width);
        }
        const double* r = received.data() + grid.Order[i] * width;
        items.push_back({ orderedBits(r[0]), r });
      }
      std::sort(items.begin(), items.end(), [](const Item& a, const Item& b) { return a.X < b.X; });
      for (auto run = items.begin(); run != items.end();)
      {
        auto end = run + 1;
        while (end != items.end() && end->X == run->X)
        {
          ++end;
        }
        if (end - run > 1)
        {
          std::sort(run, end, before);
        }
        run = end;
      }
      std::int64_t ijk[3];
      partition.Grid.Unpack(grid.CellKey[c], ijk);
      const char owned = partition.OwnerOf(ijk) == comm.Rank() ? 1 : 0;
      for (std::size_t k = 0; k < items.size(); ++k)
      {
        const std::size_t i = static_cast<std::size_t>(first) + k;
        const double* r = items[k].Record;
        for (int a = 0; a < 3; ++a)
        {
          cloud.Xyz[3 * i + a] = r[a];
        }
        cloud.Owned[i] = owned;
        cloud.SourceRank[i] = static_cast<int>(r[payloadEnd]);
        cloud.SourceId[i] = static_cast<long long>(r[payloadEnd + 1]);
        for (std::size_t a = 0; a < slots.size(); ++a)
        {
          const ArraySlot& s = slots[a];
          const std::size_t bytes = static_cast<std::size_t>(s.Components) *
            static_cast<std::size_t>(vtkDataArray::GetDataTypeSize(s.Type));
          std::memcpy(outArrays[a]->GetVoidPointer(static_cast<vtkIdType>(i) * s.Components),
            r + s.Offset, bytes);
        }
      }
    }
  });
  return cloud;
}

} // namespace asmvtk
