// SPDX-License-Identifier: BSD-3-Clause
// MPI runs: the communication helpers of vtkASMDistributed.h (collectives
// over a vtkMultiProcessController) and the test for a run under mpiexec.
#include "vtkASMDistributed.h"

#include "vtkCommunicator.h"
#include "vtkMultiProcessController.h"

#include <algorithm>
#include <cstdlib>
#include <limits>
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
    this->Ctrl->AllReduce(
      in.data(), values.data(), static_cast<vtkIdType>(in.size()), vtkCommunicator::SUM_OP);
  }
}

void Communication::Sum(std::vector<long long>& values) const
{
  if (this->Processes > 1 && !values.empty())
  {
    const std::vector<long long> in = values;
    this->Ctrl->AllReduce(
      in.data(), values.data(), static_cast<vtkIdType>(in.size()), vtkCommunicator::SUM_OP);
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
asmcore::PointArray<T> ExchangeImpl(
  vtkMultiProcessController* ctrl, int rank, int size, std::vector<asmcore::PointArray<T>>& send)
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
  asmcore::PointArray<T> received(static_cast<std::size_t>(std::max<vtkIdType>(total, 1)));
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

} // namespace

asmcore::PointArray<double> Communication::Exchange(
  std::vector<asmcore::PointArray<double>>& send) const
{
  return ExchangeImpl(this->Ctrl, this->LocalRank, this->Processes, send);
}

asmcore::PointArray<long long> Communication::Exchange(
  std::vector<asmcore::PointArray<long long>>& send) const
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

} // namespace asmvtk
