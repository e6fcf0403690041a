// SPDX-License-Identifier: BSD-3-Clause
// asm_simplify: simplify a point cloud with vtkASMSimplify from the installed
// ASM package (find_package(ASM), ASM::Filters).
//
//   asm_simplify IN OUT [--fraction F | --count N] [--tolerance EPS]
//                [--relative] [--alpha A] [--seed S] [--no-curvature]
//
// IN: .ply .vtp .xyz/.txt/.csv/.pts/.asc (text) .pcd (ascii, binary, binary_compressed);
// OUT: .ply or .vtp. Prints N, N_s, the filter's run time and its AKPE/MKPE.
// Exit status: 0 on success, 1 on bad arguments, 2 when IN cannot be read or
// OUT cannot be written, 3 when the filter fails.
#include "PointCloudIO.h"

#include "vtkASMSimplify.h"

#include "vtkCommand.h"
#include "vtkDataArray.h"
#include "vtkFieldData.h"
#include "vtkNew.h"
#include "vtkPolyData.h"

#include <cerrno>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <iostream>
#include <limits>
#include <string>

namespace
{
const char* const Usage =
  "usage: asm_simplify IN OUT [--fraction F | --count N] [--tolerance EPS] [--relative]\n"
  "                    [--alpha A] [--seed S] [--no-curvature]\n"
  "  IN   point cloud: .ply .vtp .xyz .txt .csv .pts .asc .pcd\n"
  "  OUT  simplified cloud: .ply or .vtp\n"
  "  --fraction F   keep N_s = round(F * N) points, 0 <= F <= 1 (default 0.05)\n"
  "  --count N      keep exactly N points (a whole number)\n"
  "  --tolerance E  bound the maximum key point error MKPE by E (data units; off by default)\n"
  "  --relative     E is a fraction of the bounding-box diagonal\n"
  "  --alpha A      partition threshold alpha in [0, 0.5] (default 0.125)\n"
  "  --seed S       random seed, a whole number that fits an int (default 1)\n"
  "  --no-curvature do not add the MeanCurvature arrays (faster)\n";

/// Errors of the filter (and of VTK) as text on stderr, counted.
class ErrorCounter : public vtkCommand
{
public:
  static ErrorCounter* New() { return new ErrorCounter; }
  void Execute(vtkObject*, unsigned long, void* data) override
  {
    ++this->Count;
    std::cerr << "asm_simplify: " << (data ? static_cast<const char*>(data) : "error") << "\n";
  }
  int Count = 0;
};

double FieldValue(vtkPolyData* data, const char* name)
{
  vtkDataArray* array = data->GetFieldData()->GetArray(name);
  return array && array->GetNumberOfTuples() > 0 ? array->GetTuple1(0) : -1.0;
}

/// A finite number (no inf, nan, or overflow), the whole text.
bool ParseNumber(const char* text, double& value)
{
  char* end = nullptr;
  errno = 0;
  value = std::strtod(text, &end);
  return end != text && *end == '\0' && errno != ERANGE && std::isfinite(value);
}

/// True if `value` is a whole number in [low, high].
bool IsWhole(double value, double low, double high)
{
  return value >= low && value <= high && value == std::floor(value);
}
} // namespace

int main(int argc, char* argv[])
{
  std::string input, output;
  vtkNew<vtkASMSimplify> asmFilter;
  for (int i = 1; i < argc; ++i)
  {
    const std::string arg = argv[i];
    if (arg == "-h" || arg == "--help")
    {
      std::cout << Usage;
      return 0;
    }
    if (arg == "--relative" || arg == "--no-curvature")
    {
      arg == "--relative" ? asmFilter->SetRelativeErrorTolerance(true)
                          : asmFilter->SetGenerateCurvature(false);
      continue;
    }
    if (arg.rfind("--", 0) == 0)
    {
      double value = 0;
      if (i + 1 >= argc || !ParseNumber(argv[i + 1], value))
      {
        std::cerr << "asm_simplify: " << arg << " needs a finite number\n" << Usage;
        return 1;
      }
      ++i;
      if (arg == "--fraction" && value >= 0 && value <= 1)
      {
        asmFilter->SetTargetModeToOutputFraction();
        asmFilter->SetOutputFraction(value);
      }
      else if (arg == "--count" && IsWhole(value, 0, 9007199254740992.0)) // 2^53
      {
        asmFilter->SetTargetModeToNumberOfOutputPoints();
        asmFilter->SetNumberOfOutputPoints(static_cast<vtkIdType>(value));
      }
      else if (arg == "--tolerance" && value >= 0)
        asmFilter->SetErrorTolerance(value);
      else if (arg == "--alpha" && value >= 0 && value <= 0.5)
        asmFilter->SetAlpha(value);
      else if (arg == "--seed" &&
        IsWhole(value, std::numeric_limits<int>::min(), std::numeric_limits<int>::max()))
        asmFilter->SetRandomSeed(static_cast<int>(value));
      else
      {
        std::cerr << "asm_simplify: bad option or value: " << arg << " " << argv[i] << "\n"
                  << Usage;
        return 1;
      }
      continue;
    }
    if (!output.empty())
    {
      std::cerr << "asm_simplify: unexpected argument " << arg << "\n" << Usage;
      return 1;
    }
    (input.empty() ? input : output) = arg;
  }
  if (input.empty() || output.empty())
  {
    std::cerr << Usage;
    return 1;
  }
  const std::string outExt = pcio::Extension(output);
  if (outExt != "ply" && outExt != "vtp")
  {
    std::cerr << "asm_simplify: OUT must end in .ply or .vtp: " << output << "\n";
    return 1;
  }

  std::string error;
  auto cloud = pcio::ReadPointCloud(input, error);
  if (!cloud)
  {
    std::cerr << "asm_simplify: " << error << "\n";
    return 2;
  }

  vtkNew<ErrorCounter> errors;
  asmFilter->AddObserver(vtkCommand::ErrorEvent, errors);
  asmFilter->SetInputData(cloud);
  const auto start = std::chrono::steady_clock::now();
  asmFilter->Update();
  const double seconds =
    std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  vtkPolyData* simplified = asmFilter->GetOutput();
  if (errors->Count > 0)
  {
    return 3;
  }

  if (!pcio::WritePointCloud(simplified, output, error))
  {
    std::cerr << "asm_simplify: " << error << "\n";
    return 2;
  }
  std::printf("input      : %s\n", input.c_str());
  std::printf("N          : %lld\n", static_cast<long long>(cloud->GetNumberOfPoints()));
  std::printf("N_s        : %lld\n", static_cast<long long>(simplified->GetNumberOfPoints()));
  std::printf("key points : %.0f\n", FieldValue(simplified, "NumberOfKeyPoints"));
  std::printf("cell size  : %.6g\n", FieldValue(simplified, "CellSize"));
  std::printf("time (s)   : %.4f\n", seconds);
  std::printf("AKPE       : %.6g\n", FieldValue(simplified, "AKPE"));
  std::printf("MKPE       : %.6g\n", FieldValue(simplified, "MKPE"));
  std::printf("output     : %s\n", output.c_str());
  return 0;
}
