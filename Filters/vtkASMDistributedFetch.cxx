// SPDX-License-Identifier: BSD-3-Clause
// MPI runs: the string, variant and bit arrays, which do not travel with the
// points, read for the samples at their representatives after the run
// (FetchRepresentativeValues, vtkASMDistributed.h).
#include "vtkASMDistributed.h"
#include "vtkASMPointDataAggregation.h"

#include "vtkAbstractArray.h"
#include "vtkBitArray.h"
#include "vtkPointData.h"
#include "vtkSmartPointer.h"
#include "vtkStringArray.h"
#include "vtkVariant.h"
#include "vtkVariantArray.h"

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <numeric>
#include <string>

namespace asmvtk
{
namespace
{
// Messages are runs of long longs: a size in bytes, then the bytes (ids, or
// encoded values) packed 8 to a value. Every process sends one message to
// every process, empty ones included, so that the received runs come one
// per process, in process order.
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

// The messages of `received`, one per process: (first byte, size in bytes);
// false when they do not add up.
bool SplitMessages(const asmcore::PointArray<long long>& received, int processes,
  std::vector<std::pair<const char*, std::size_t>>& messages)
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
    messages.emplace_back(reinterpret_cast<const char*>(received.data() + at + 1), size);
    at += 1 + words;
  }
  return at == received.size();
}

// The values' encoding, exact for every type (VTK's legacy marshalling
// writes variants with 6 digits): a bit as a byte; a string as its length
// (8 bytes) and bytes; a variant as a kind byte, its VTK type (4 bytes) and
// a string, or a number as 8 bytes (floating types as a double, integers as
// 64-bit integers); a variant holding anything else (a VTK object) as an
// empty one.
enum VariantKind : unsigned char
{
  Empty = 0,
  Text = 1,
  Floating = 2,
  Signed = 3,
  Unsigned = 4,
};

class Writer
{
public:
  std::vector<char> Bytes;
  template <typename T>
  void Put(const T& value)
  {
    const char* p = reinterpret_cast<const char*>(&value);
    this->Bytes.insert(this->Bytes.end(), p, p + sizeof(T));
  }
  void PutString(const std::string& s)
  {
    this->Put(static_cast<std::uint64_t>(s.size()));
    this->Bytes.insert(this->Bytes.end(), s.begin(), s.end());
  }
  void PutVariant(const vtkVariant& v)
  {
    const int type = v.IsValid() ? static_cast<int>(v.GetType()) : 0;
    if (v.IsString())
    {
      this->Put(static_cast<unsigned char>(Text));
      this->Put(type);
      this->PutString(v.ToString());
    }
    else if (v.IsFloat() || v.IsDouble())
    {
      this->Put(static_cast<unsigned char>(Floating));
      this->Put(type);
      this->Put(v.ToDouble());
    }
    else if (v.IsNumeric() && (type == VTK_UNSIGNED_LONG_LONG || type == VTK_UNSIGNED_LONG))
    {
      this->Put(static_cast<unsigned char>(Unsigned));
      this->Put(type);
      this->Put(static_cast<std::uint64_t>(v.ToUnsignedLongLong()));
    }
    else if (v.IsNumeric())
    {
      this->Put(static_cast<unsigned char>(Signed));
      this->Put(type);
      this->Put(static_cast<std::int64_t>(v.ToLongLong()));
    }
    else
    {
      this->Put(static_cast<unsigned char>(Empty));
    }
  }
};

class Reader
{
public:
  Reader(const char* data, std::size_t size)
    : At(data)
    , End(data + size)
  {
  }
  bool Good() const { return this->Ok; }
  bool Finished() const { return this->Ok && this->At == this->End; }
  template <typename T>
  T Get()
  {
    T value{};
    if (!this->Ok || static_cast<std::size_t>(this->End - this->At) < sizeof(T))
    {
      this->Ok = false;
      return value;
    }
    std::memcpy(&value, this->At, sizeof(T));
    this->At += sizeof(T);
    return value;
  }
  std::string GetString()
  {
    const auto size = this->Get<std::uint64_t>();
    if (!this->Ok || static_cast<std::uint64_t>(this->End - this->At) < size)
    {
      this->Ok = false;
      return {};
    }
    std::string s(this->At, static_cast<std::size_t>(size));
    this->At += size;
    return s;
  }
  vtkVariant GetVariant()
  {
    const auto kind = this->Get<unsigned char>();
    if (kind == Empty)
    {
      return {};
    }
    const auto type = static_cast<unsigned int>(this->Get<int>());
    vtkVariant value;
    switch (kind)
    {
      case Text:
        value = vtkVariant(this->GetString());
        break;
      case Floating:
        value = vtkVariant(this->Get<double>());
        break;
      case Signed:
        value = vtkVariant(static_cast<long long>(this->Get<std::int64_t>()));
        break;
      case Unsigned:
        value = vtkVariant(static_cast<unsigned long long>(this->Get<std::uint64_t>()));
        break;
      default:
        this->Ok = false;
        return {};
    }
    // (Back to the type it had: a float, a char, a vtkStdString...)
    return type == value.GetType() ? value : vtkVariant(value, type);
  }

private:
  const char* At;
  const char* End;
  bool Ok = true;
};

// Writes value `component` of tuple `id` of `array` (a string, variant or
// bit array).
void Encode(vtkAbstractArray* array, vtkIdType id, int component, Writer& out)
{
  const vtkIdType at = id * array->GetNumberOfComponents() + component;
  if (auto* strings = vtkStringArray::SafeDownCast(array))
  {
    out.PutString(strings->GetValue(at));
  }
  else if (auto* variants = vtkVariantArray::SafeDownCast(array))
  {
    out.PutVariant(variants->GetValue(at));
  }
  else
  {
    out.Put(static_cast<unsigned char>(vtkBitArray::SafeDownCast(array)->GetValue(at)));
  }
}

// Reads value `component` of tuple `s` of `array` (of the same kind).
void Decode(Reader& in, vtkAbstractArray* array, vtkIdType s, int component)
{
  const vtkIdType at = s * array->GetNumberOfComponents() + component;
  if (auto* strings = vtkStringArray::SafeDownCast(array))
  {
    strings->SetValue(at, in.GetString());
  }
  else if (auto* variants = vtkVariantArray::SafeDownCast(array))
  {
    variants->SetValue(at, in.GetVariant());
  }
  else
  {
    vtkBitArray::SafeDownCast(array)->SetValue(at, in.Get<unsigned char>() ? 1 : 0);
  }
}

// Puts the arrays of `pd` named in `order` first, in that order (the others
// after them, as they were), keeping the attribute roles.
void PlaceInOrder(vtkPointData* pd, const std::vector<std::string>& order)
{
  std::vector<vtkSmartPointer<vtkAbstractArray>> arrays;
  for (const std::string& name : order)
  {
    if (vtkAbstractArray* array = pd->GetAbstractArray(name.c_str()))
    {
      arrays.emplace_back(array);
    }
  }
  for (int i = 0; i < pd->GetNumberOfArrays(); ++i)
  {
    vtkAbstractArray* array = pd->GetAbstractArray(i);
    if (std::find(arrays.begin(), arrays.end(), array) == arrays.end())
    {
      arrays.emplace_back(array);
    }
  }
  std::vector<int> roles(arrays.size(), 0); // bit a: the array is attribute a
  for (std::size_t i = 0; i < arrays.size(); ++i)
  {
    for (int a = 0; a < vtkDataSetAttributes::NUM_ATTRIBUTES; ++a)
    {
      roles[i] |= pd->GetAbstractAttribute(a) == arrays[i] ? 1 << a : 0;
    }
  }
  while (pd->GetNumberOfArrays() > 0)
  {
    pd->RemoveArray(pd->GetNumberOfArrays() - 1);
  }
  for (std::size_t i = 0; i < arrays.size(); ++i)
  {
    const int index = pd->AddArray(arrays[i]);
    for (int a = 0; a < vtkDataSetAttributes::NUM_ATTRIBUTES; ++a)
    {
      if (roles[i] & (1 << a))
      {
        pd->SetActiveAttribute(index, a);
      }
    }
  }
}
} // namespace

bool FetchRepresentativeValues(const Communication& comm, vtkPointData* inputPD,
  const LocalCloud& cloud, const std::vector<std::pair<vtkIdType, Index>>& ties,
  asmcore::SimplifyResult& result, vtkPointData* fetchedPD)
{
  const std::vector<FetchedArray>& fetched = cloud.Fetched;
  if (fetched.empty()) // (the same on every process: agreed in Redistribute)
  {
    return true;
  }
  const int processes = comm.Size();
  const auto count = static_cast<vtkIdType>(result.Samples.size());
  // The rows asked for: one per sample (its representative), in sample
  // order, then one per tie (another candidate for that sample).
  std::vector<Index> rowPoint(static_cast<std::size_t>(count) + ties.size());
  for (vtkIdType s = 0; s < count; ++s)
  {
    rowPoint[s] = result.Samples[s].Representative;
  }
  for (std::size_t t = 0; t < ties.size(); ++t)
  {
    rowPoint[count + t] = ties[t].second;
  }
  const auto rows = static_cast<vtkIdType>(rowPoint.size());
  // 1. Requests: the rows' point ids, to the processes holding them
  // (rowsFrom[r]: the rows whose values r sends, in increasing order).
  std::vector<std::vector<vtkIdType>> rowsFrom(static_cast<std::size_t>(processes));
  for (vtkIdType row = 0; row < rows; ++row)
  {
    rowsFrom[cloud.SourceRank[rowPoint[row]]].push_back(row);
  }
  std::vector<asmcore::PointArray<long long>> send(static_cast<std::size_t>(processes));
  std::vector<long long> asked;
  for (int r = 0; r < processes; ++r)
  {
    asked.clear();
    for (vtkIdType row : rowsFrom[r])
    {
      asked.push_back(cloud.SourceId[rowPoint[row]]);
    }
    AppendMessage(send[r], asked.data(), asked.size() * sizeof(long long));
  }
  const asmcore::PointArray<long long> requests = comm.Exchange(send);
  std::vector<std::pair<const char*, std::size_t>> messages;
  bool readable = SplitMessages(requests, processes, messages);

  // 2. Replies: the values at the ids each process asked for, in its order,
  // array by array.
  std::vector<vtkAbstractArray*> sources;
  for (const FetchedArray& f : fetched)
  {
    sources.push_back(inputPD ? inputPD->GetAbstractArray(f.Name.c_str()) : nullptr);
  }
  send.assign(static_cast<std::size_t>(processes), {});
  Writer writer;
  for (int r = 0; r < processes; ++r)
  {
    const std::size_t asks = readable ? messages[r].second / sizeof(long long) : 0;
    writer.Bytes.clear();
    for (std::size_t a = 0; asks > 0 && a < fetched.size(); ++a)
    {
      for (std::size_t j = 0; j < asks; ++j)
      {
        long long id;
        std::memcpy(&id, messages[r].first + j * sizeof(long long), sizeof(id));
        // (The arrays were agreed on: a source has a tuple for every point.)
        const bool valid = sources[a] && id >= 0 && id < sources[a]->GetNumberOfTuples();
        for (int c = 0; c < fetched[a].Components; ++c)
        {
          if (valid)
          {
            Encode(sources[a], static_cast<vtkIdType>(id), c, writer);
          }
          else
          {
            readable = false;
          }
        }
      }
    }
    AppendMessage(send[r], writer.Bytes.data(), readable ? writer.Bytes.size() : 0);
  }
  const asmcore::PointArray<long long> replies = comm.Exchange(send);
  readable = SplitMessages(replies, processes, messages) && readable;

  // 3. The rows' values: rowsFrom[r] take those of r's reply, in order.
  std::vector<vtkSmartPointer<vtkAbstractArray>> values;
  for (const FetchedArray& f : fetched)
  {
    auto array = vtk::TakeSmartPointer(vtkAbstractArray::CreateArray(f.Type));
    array->SetName(f.Name.c_str());
    array->SetNumberOfComponents(f.Components);
    array->SetNumberOfTuples(rows);
    values.push_back(array);
  }
  for (int r = 0; readable && r < processes; ++r)
  {
    Reader reader(messages[r].first, messages[r].second);
    for (std::size_t a = 0; a < fetched.size(); ++a)
    {
      for (vtkIdType row : rowsFrom[r])
      {
        for (int c = 0; c < fetched[a].Components; ++c)
        {
          Decode(reader, values[a], row, c);
        }
      }
    }
    readable = reader.Finished();
  }
  if (!readable)
  {
    return false;
  }

  // 4. Among a sample's ties, the row whose values come first (ties: the
  // representative's row, then the lower row) gives the sample its
  // representative and its values.
  auto before = [&values](vtkIdType a, vtkIdType b) {
    for (const auto& array : values)
    {
      if (const int order = CompareTuples(array, a, b))
      {
        return order < 0;
      }
    }
    return false;
  };
  std::vector<vtkIdType> chosen(static_cast<std::size_t>(count));
  std::iota(chosen.begin(), chosen.end(), vtkIdType(0));
  for (std::size_t t = 0; t < ties.size(); ++t)
  {
    const vtkIdType s = ties[t].first;
    const vtkIdType row = count + static_cast<vtkIdType>(t);
    if (before(row, chosen[s]))
    {
      chosen[s] = row;
      result.Samples[s].Representative = rowPoint[row];
    }
  }
  for (auto& array : values)
  {
    if (!ties.empty())
    {
      auto samples = vtk::TakeSmartPointer(array->NewInstance());
      samples->SetName(array->GetName());
      samples->SetNumberOfComponents(array->GetNumberOfComponents());
      samples->SetNumberOfTuples(count);
      for (vtkIdType s = 0; s < count; ++s)
      {
        samples->SetTuple(s, chosen[s], array);
      }
      array = samples;
    }
    fetchedPD->AddArray(array);
  }
  return true;
}

void AddFetchedArrays(vtkPointData* fetchedPD, const LocalCloud& cloud, vtkPointData* outPD)
{
  if (cloud.Fetched.empty())
  {
    return; // (the output's arrays are in the input's order already)
  }
  for (int i = 0; i < fetchedPD->GetNumberOfArrays(); ++i)
  {
    outPD->AddArray(fetchedPD->GetAbstractArray(i));
  }
  PlaceInOrder(outPD, cloud.ArrayOrder);
}
} // namespace asmvtk
