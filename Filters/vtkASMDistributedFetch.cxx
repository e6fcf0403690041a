// SPDX-License-Identifier: BSD-3-Clause
// MPI runs: the string, variant and bit arrays, which do not travel with the
// points, read for the samples at their representatives after the run
// (FetchRepresentativeValues, vtkASMDistributed.h).
#include "vtkASMDistributed.h"

#include "vtkAbstractArray.h"
#include "vtkCharArray.h"
#include "vtkCommunicator.h"
#include "vtkDataArray.h"
#include "vtkNew.h"
#include "vtkPointData.h"
#include "vtkSmartPointer.h"
#include "vtkTable.h"

#include <cstring>

namespace asmvtk
{
namespace
{
// Messages are runs of long longs: a count, then that many values (ids, or
// the bytes of a marshalled vtkTable packed 8 to a value). Every process
// sends one message to every process, empty ones included, so that the
// received runs come one per process, in process order.
void AppendMessage(asmcore::PointArray<long long>& to, const void* bytes, std::size_t size)
{
  const std::size_t at = to.size();
  to.resize(at + 1 + (size + 7) / 8, 0);
  to[at] = static_cast<long long>(size);
  if (size > 0)
  {
    std::memcpy(to.data() + at + 1, bytes, size);
  }
}

// The messages of `received`, one per process: (first value, size in bytes);
// false when they do not add up.
bool SplitMessages(const asmcore::PointArray<long long>& received, int processes,
  std::vector<std::pair<const long long*, std::size_t>>& messages)
{
  messages.clear();
  std::size_t at = 0;
  for (int r = 0; r < processes; ++r)
  {
    if (at >= received.size() || received[at] < 0)
    {
      return false;
    }
    const auto size = static_cast<std::size_t>(received[at]);
    const std::size_t words = (size + 7) / 8;
    if (words > received.size() - at - 1)
    {
      return false;
    }
    messages.emplace_back(received.data() + at + 1, size);
    at += 1 + words;
  }
  return at == received.size();
}

// The type an array's values travel as: bit arrays as unsigned chars (VTK's
// legacy reader, which unmarshals the tables, fails on some binary bit
// arrays).
int TransportType(int type)
{
  return type == VTK_BIT ? VTK_UNSIGNED_CHAR : type;
}

// to[i] = from[j], tuples of arrays of one type, or of two numeric types.
void CopyTuple(vtkAbstractArray* to, vtkIdType i, vtkAbstractArray* from, vtkIdType j)
{
  auto* numericTo = vtkDataArray::SafeDownCast(to);
  auto* numericFrom = vtkDataArray::SafeDownCast(from);
  if (numericTo && numericFrom && to->GetDataType() != from->GetDataType())
  {
    for (int c = 0; c < to->GetNumberOfComponents(); ++c)
    {
      numericTo->SetComponent(i, c, numericFrom->GetComponent(j, c));
    }
    return;
  }
  to->SetTuple(i, j, from);
}
} // namespace

bool FetchRepresentativeValues(const Communication& comm, vtkPointData* inputPD,
  const LocalCloud& cloud, const asmcore::SimplifyResult& result, vtkPointData* outPD)
{
  const std::vector<FetchedArray>& fetched = cloud.Fetched;
  if (fetched.empty()) // (the same on every process: agreed in Redistribute)
  {
    return true;
  }
  const int processes = comm.Size();
  const auto count = static_cast<vtkIdType>(result.Samples.size());
  // 1. Requests: the representatives' ids, to the processes holding them,
  // in sample order.
  std::vector<std::vector<long long>> asked(static_cast<std::size_t>(processes));
  for (const asmcore::Sample& sample : result.Samples)
  {
    const Index r = sample.Representative;
    asked[cloud.SourceRank[r]].push_back(cloud.SourceId[r]);
  }
  std::vector<asmcore::PointArray<long long>> send(static_cast<std::size_t>(processes));
  for (int r = 0; r < processes; ++r)
  {
    AppendMessage(send[r], asked[r].data(), asked[r].size() * sizeof(long long));
  }
  const asmcore::PointArray<long long> requests = comm.Exchange(send);
  std::vector<std::pair<const long long*, std::size_t>> messages;
  bool readable = SplitMessages(requests, processes, messages);

  // 2. Replies: the values at the ids each process asked for, in its order,
  // as the rows of a table (any array type; marshalled by VTK).
  send.assign(static_cast<std::size_t>(processes), {});
  for (int r = 0; r < processes; ++r)
  {
    const std::size_t rows = readable ? messages[r].second / sizeof(long long) : 0;
    if (rows == 0)
    {
      AppendMessage(send[r], nullptr, 0);
      continue;
    }
    vtkNew<vtkTable> table;
    for (const FetchedArray& f : fetched)
    {
      vtkAbstractArray* source = inputPD->GetAbstractArray(f.Name.c_str());
      auto column = vtk::TakeSmartPointer(vtkAbstractArray::CreateArray(TransportType(f.Type)));
      column->SetName(f.Name.c_str());
      column->SetNumberOfComponents(f.Components);
      column->SetNumberOfTuples(static_cast<vtkIdType>(rows));
      for (std::size_t j = 0; j < rows; ++j)
      {
        const long long id = messages[r].first[j];
        if (source && id >= 0 && id < source->GetNumberOfTuples())
        {
          CopyTuple(column, static_cast<vtkIdType>(j), source, static_cast<vtkIdType>(id));
        }
      }
      table->AddColumn(column);
    }
    vtkNew<vtkCharArray> bytes;
    vtkCommunicator::MarshalDataObject(table, bytes);
    AppendMessage(send[r], bytes->GetPointer(0), static_cast<std::size_t>(bytes->GetNumberOfValues()));
  }
  const asmcore::PointArray<long long> replies = comm.Exchange(send);
  readable = SplitMessages(replies, processes, messages) && readable;

  // 3. The output arrays: sample s takes the next row of the table from the
  // process that holds its representative.
  std::vector<vtkSmartPointer<vtkTable>> tables(static_cast<std::size_t>(processes));
  std::vector<std::vector<vtkAbstractArray*>> columns(static_cast<std::size_t>(processes));
  for (int r = 0; readable && r < processes; ++r)
  {
    if (messages[r].second == 0)
    {
      readable = asked[r].empty();
      continue;
    }
    vtkNew<vtkCharArray> bytes;
    bytes->SetNumberOfValues(static_cast<vtkIdType>(messages[r].second));
    std::memcpy(bytes->GetPointer(0), messages[r].first, messages[r].second);
    tables[r] = vtkSmartPointer<vtkTable>::New();
    readable = vtkCommunicator::UnMarshalDataObject(bytes, tables[r]) != 0 &&
      tables[r]->GetNumberOfRows() == static_cast<vtkIdType>(asked[r].size());
    for (std::size_t a = 0; readable && a < fetched.size(); ++a)
    {
      vtkAbstractArray* column = tables[r]->GetColumnByName(fetched[a].Name.c_str());
      readable = column && column->GetDataType() == TransportType(fetched[a].Type) &&
        column->GetNumberOfComponents() == fetched[a].Components;
      columns[r].push_back(column);
    }
  }
  if (!readable)
  {
    return false;
  }
  std::vector<vtkIdType> next(static_cast<std::size_t>(processes), 0);
  std::vector<vtkSmartPointer<vtkAbstractArray>> arrays;
  for (const FetchedArray& f : fetched)
  {
    auto array = vtk::TakeSmartPointer(vtkAbstractArray::CreateArray(f.Type));
    array->SetName(f.Name.c_str());
    array->SetNumberOfComponents(f.Components);
    array->SetNumberOfTuples(count);
    arrays.push_back(array);
  }
  for (vtkIdType s = 0; s < count; ++s)
  {
    const int r = cloud.SourceRank[result.Samples[s].Representative];
    const vtkIdType row = next[r]++;
    for (std::size_t a = 0; a < fetched.size(); ++a)
    {
      CopyTuple(arrays[a], s, columns[r][a], row);
    }
  }
  for (const auto& array : arrays)
  {
    outPD->AddArray(array);
  }
  return true;
}
} // namespace asmvtk
