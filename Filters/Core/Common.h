// SPDX-License-Identifier: BSD-3-Clause
/**
 * Common vocabulary of the ASM core: plain C++17, no VTK types.
 *
 * The core works on a point cloud given as N x 3 doubles (x0 y0 z0 x1 ...)
 * and a list of the point ids to use (the finite ones). Parallel loops and
 * progress reporting are injected by the caller (vtkSMPTools and
 * vtkAlgorithm::UpdateProgress in the VTK filters, plain loops in tests), so
 * the geometry can be tested on its own.
 */
#ifndef asm_core_Common_h
#define asm_core_Common_h

#include "vtkASMFiltersModule.h" // For export macro

#include <algorithm>
#include <array>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <functional>
#include <iterator>
#include <memory>
#include <new>
#include <type_traits>
#include <utility>
#include <vector>

namespace asmcore
{
/// Point and cell index type: 64-bit end to end.
using Index = std::int64_t;
/// A sample's number in the per-point assignments of the default mode: 32
/// bits (4 bytes per point less), so at most 2^31 - 1 samples there.
using SampleId = std::int32_t;

/// Runs body(b, e) over sub-ranges covering [begin, end); may run them
/// concurrently. Results must not depend on how the range is cut.
using ParallelFor =
  std::function<void(Index begin, Index end, const std::function<void(Index, Index)>& body)>;

/// Called with the fraction of work done, in [0, 1]; returns true to abort.
using ProgressCallback = std::function<bool(double)>;

/// How the caller runs the core's loops.
struct Execution
{
  ParallelFor For;           ///< empty: sequential
  ProgressCallback Progress; ///< empty: no reports, never aborts

  void Run(Index begin, Index end, const std::function<void(Index, Index)>& body) const
  {
    if (begin >= end)
    {
      return;
    }
    if (this->For)
    {
      this->For(begin, end, body);
    }
    else
    {
      // On the calling thread, in SequentialPieces pieces as vtkSMPTools
      // splits a loop for one thread: loops keep scratch sized by their
      // piece (a chunk's cluster sums, say), which one piece would make as
      // large as the whole range (heap peak 69.2 MB instead of 62.0 at 1 M
      // points, 20 %, default mode). The result does not depend on the pieces.
      const Index n = end - begin;
      const Index pieces = std::min<Index>(SequentialPieces, n);
      for (Index k = 0; k < pieces; ++k)
      {
        body(begin + n * k / pieces, begin + n * (k + 1) / pieces);
      }
    }
  }
  static constexpr Index SequentialPieces = 4;
  bool Report(double fraction) const { return this->Progress ? this->Progress(fraction) : false; }
};

/// A hint to start loading the cache line at `p` (a no-op where unsupported):
/// for loops that gather points scattered in memory.
inline void Prefetch(const void* p)
{
#if defined(__GNUC__) || defined(__clang__)
  __builtin_prefetch(p);
#else
  (void)p;
#endif
}

/// Copies one point's three coordinates. In per-point loops, prefer it to
/// std::copy of three doubles, which GCC turns into a call to memmove: a
/// gather of 4 M scattered points into cell order took 170-210 ms that way
/// and 75-85 ms with three assignments (one thread).
inline void CopyPoint(const double* from, double* to)
{
  to[0] = from[0];
  to[1] = from[1];
  to[2] = from[2];
}

/// A std::allocator that default-initialises: resize() leaves numbers
/// uninitialised instead of zero-filling them serially. For large per-point
/// arrays that a parallel loop writes in full before anything reads them
/// (their pages are then first touched by that loop, on every thread).
/// With Unwritten, resize() writes nothing even for a type with default
/// member initialisers (ResizeInParallel then writes them).
template <typename T, bool Unwritten = false>
struct DefaultInitAllocator : std::allocator<T>
{
  template <typename U>
  struct rebind
  {
    using other = DefaultInitAllocator<U, Unwritten>;
  };
  DefaultInitAllocator() noexcept = default;
  template <typename U>
  DefaultInitAllocator(const DefaultInitAllocator<U, Unwritten>&) noexcept
  {
  }
  template <typename U>
  void construct(U* p) noexcept(std::is_nothrow_default_constructible<U>::value)
  {
    if constexpr (Unwritten)
    {
      static_assert(
        std::is_trivially_copyable<U>::value && std::is_trivially_destructible<U>::value,
        "only plain aggregates may be left unwritten");
      (void)p;
    }
    else
    {
      ::new (static_cast<void*>(p)) U;
    }
  }
  template <typename U, typename... Args>
  void construct(U* p, Args&&... args)
  {
    ::new (static_cast<void*>(p)) U(std::forward<Args>(args)...);
  }
};

/// A per-point array whose resize() does not zero-fill (DefaultInitAllocator).
template <typename T>
using PointArray = std::vector<T, DefaultInitAllocator<T>>;

/// An array of plain aggregates whose resize() writes nothing, not even
/// their default member initialisers: grown by ResizeInParallel.
template <typename T>
using UnwrittenArray = std::vector<T, DefaultInitAllocator<T, true>>;

/// Resizes `array` to n elements, the new ones set to `value` by a parallel
/// loop (which first-touches their pages on every thread).
template <typename T>
void ResizeInParallel(
  UnwrittenArray<T>& array, std::size_t n, const T& value, const Execution& execution)
{
  const auto old = static_cast<Index>(array.size());
  array.resize(n);
  execution.Run(old, static_cast<Index>(n),
    [&](Index b, Index e) { std::fill(array.begin() + b, array.begin() + e, value); });
}

/// A list of point ids that a parallel loop fills (no serial zero fill).
using PointIds = PointArray<Index>;

/// A read-only view of a list of point ids (indices into an xyz array): what
/// the steps take, so that a caller may hold its ids in a std::vector or in
/// a PointArray (which a parallel loop fills without a serial zero fill), or
/// hold none at all: IdView::Identity(n) stands for the ids 0, 1, ..., n - 1
/// (a cloud whose points are all valid) without 8 bytes per point.
/// It does not own the ids: the list must outlive the call.
class IdView
{
public:
  /// Reads the ids in order (a counter for the identity).
  class Iterator
  {
  public:
    using iterator_category = std::forward_iterator_tag;
    using value_type = Index;
    using difference_type = std::ptrdiff_t;
    using pointer = const Index*;
    using reference = Index;

    Iterator(const Index* first, Index start, std::size_t i)
      : First(first)
      , Start(start)
      , I(i)
    {
    }
    Index operator*() const
    {
      return this->First ? this->First[this->I] : this->Start + static_cast<Index>(this->I);
    }
    Iterator& operator++()
    {
      ++this->I;
      return *this;
    }
    Iterator operator++(int)
    {
      Iterator old = *this;
      ++this->I;
      return old;
    }
    bool operator==(const Iterator& other) const { return this->I == other.I; }
    bool operator!=(const Iterator& other) const { return this->I != other.I; }

  private:
    const Index* First;
    Index Start;
    std::size_t I;
  };

  IdView() = default;
  template <typename Allocator>
  IdView(const std::vector<Index, Allocator>& ids) // NOLINT: implicit on purpose
    : First(ids.data())
    , Count(ids.size())
    , Listed(true)
  {
  }
  IdView(const Index* first, std::size_t count)
    : First(first)
    , Count(count)
    , Listed(true)
  {
  }
  /// The ids 0, 1, ..., count - 1, with no list behind them.
  static IdView Identity(std::size_t count) { return Range(0, count); }
  /// The ids first, first + 1, ..., first + count - 1 (e.g. the slots of a
  /// grid cell in slot order), with no list behind them.
  static IdView Range(Index first, std::size_t count)
  {
    IdView range;
    range.Start = first;
    range.Count = count;
    return range;
  }
  /// True for Identity() (an empty list is both).
  bool IsIdentity() const { return !this->Listed && this->Start == 0; }
  std::size_t size() const { return this->Count; }
  bool empty() const { return this->Count == 0; }
  Iterator begin() const { return Iterator(this->List(), this->Start, 0); }
  Iterator end() const { return Iterator(this->List(), this->Start, this->Count); }
  Index operator[](std::size_t i) const
  {
    return this->Listed ? this->First[i] : this->Start + static_cast<Index>(i);
  }
  /// The list (nullptr for a range, whose ids are RangeStart() + i).
  const Index* ListData() const { return this->List(); }
  Index RangeStart() const { return this->Start; }

private:
  // (nullptr for the identity, which the iterator reads as a counter.)
  const Index* List() const { return this->Listed ? this->First : nullptr; }

  const Index* First = nullptr;
  Index Start = 0; ///< (Identity and Range: the first id)
  std::size_t Count = 0;
  bool Listed = false;
};

/// Three floats or three doubles per point, read where they are (floats
/// widened exactly): the input coordinates (a float cloud needs no double
/// copy for its grid) or its optional normals. Converts from a double
/// pointer, a float pointer or nullptr (none).
struct Vec3Field
{
  const double* Doubles = nullptr;
  const float* Floats = nullptr;

  Vec3Field() = default;
  Vec3Field(std::nullptr_t) {}     // NOLINT: implicit on purpose
  Vec3Field(const double* doubles) // NOLINT: implicit on purpose
    : Doubles(doubles)
  {
  }
  Vec3Field(const float* floats) // NOLINT: implicit on purpose
    : Floats(floats)
  {
  }
  explicit operator bool() const { return this->Doubles || this->Floats; }
  /// The three numbers of point `id` into out[3].
  void Get(Index id, double out[3]) const
  {
    if (this->Doubles)
    {
      CopyPoint(this->Doubles + 3 * id, out);
      return;
    }
    const float* p = this->Floats + 3 * id;
    out[0] = static_cast<double>(p[0]);
    out[1] = static_cast<double>(p[1]);
    out[2] = static_cast<double>(p[2]);
  }
  /// Point `id` as three doubles (a value: for a call that takes double[3]).
  std::array<double, 3> At(Index id) const
  {
    std::array<double, 3> p;
    this->Get(id, p.data());
    return p;
  }
  /// Where point `id`'s numbers are (for a prefetch).
  const void* Address(Index id) const
  {
    return this->Doubles ? static_cast<const void*>(this->Doubles + 3 * id)
                         : static_cast<const void*>(this->Floats + 3 * id);
  }
};
/// Optional input normals.
using NormalField = Vec3Field;

/// Input coordinates, doubles or floats.
using Coordinates = Vec3Field;

/// Calls f(i, p) for i in [begin, end), p the three numbers of point ids[i]:
/// one loop per storage (floats or doubles) and kind of ids (a list or a
/// range), so that the loop tests neither per point (for streaming passes).
template <typename F>
inline void ForEachPoint(Vec3Field xyz, IdView ids, Index begin, Index end, F&& f)
{
  auto loop = [&](auto* numbers, auto idOf) {
    for (Index i = begin; i < end; ++i)
    {
      const auto* q = numbers + 3 * idOf(i);
      const double p[3] = { static_cast<double>(q[0]), static_cast<double>(q[1]),
        static_cast<double>(q[2]) };
      f(i, p);
    }
  };
  const Index* list = ids.ListData();
  const Index start = ids.RangeStart();
  auto listed = [list](Index i) { return list[i]; };
  auto ranged = [start](Index i) { return start + i; };
  if (xyz.Doubles)
  {
    list ? loop(xyz.Doubles, listed) : loop(xyz.Doubles, ranged);
  }
  else
  {
    list ? loop(xyz.Floats, listed) : loop(xyz.Floats, ranged);
  }
}

/// Ids of the points whose three coordinates are finite.
VTKASMFILTERS_EXPORT std::vector<Index> FinitePointIds(const double* xyz, Index n);

/// SplitMix64: a small, portable, well-mixed 64-bit generator. Used for the
/// per-cell random choices so that results do not depend on the thread that
/// processes a cell.
class SplitMix64
{
public:
  explicit SplitMix64(std::uint64_t seed)
    : State(seed)
  {
  }
  std::uint64_t Next()
  {
    std::uint64_t z = (this->State += 0x9E3779B97F4A7C15ULL);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ULL;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBULL;
    return z ^ (z >> 31);
  }
  /// Uniform integer in [0, bound), bound > 0.
  std::uint64_t Below(std::uint64_t bound)
  {
    // Rejection sampling keeps the draw unbiased.
    const std::uint64_t limit = ~std::uint64_t(0) - (~std::uint64_t(0) % bound);
    std::uint64_t r;
    do
    {
      r = this->Next();
    } while (r >= limit);
    return r % bound;
  }

private:
  std::uint64_t State;
};

/// Lexicographic order of two positions: the order-independent tie-break.
inline bool PositionBefore(const double* a, const double* b)
{
  return std::lexicographical_compare(a, a + 3, b, b + 3);
}

/// Point (a, idA) before point (b, idB): by position, then, between exact
/// duplicates, by id.
inline bool PositionThenIdBefore(const double* a, Index idA, const double* b, Index idB)
{
  return PositionBefore(a, b) || (!PositionBefore(b, a) && idA < idB);
}

/// A well-mixed 64-bit hash of a point's three coordinates (their bits): a
/// function of the position alone, whatever the point's id or place in the
/// input.
inline std::uint64_t CoordinateHash(const double* p)
{
  std::uint64_t bits[3];
  std::memcpy(bits, p, sizeof(bits));
  SplitMix64 mix(
    bits[0] ^ ((bits[1] << 21) | (bits[1] >> 43)) ^ ((bits[2] << 42) | (bits[2] >> 22)));
  return mix.Next();
}
} // namespace asmcore

#endif
