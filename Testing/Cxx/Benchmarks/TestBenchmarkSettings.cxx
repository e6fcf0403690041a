// SPDX-License-Identifier: BSD-3-Clause
// The benchmarks' --asm variants: vtkASMSimplify's properties set by name
// (ApplyAsmSettings, ParseAsmVariant), and a variant's run differing from
// the standard configuration by its settings only.
#include "BenchmarkData.h"
#include "BenchmarkMethods.h"

#include "vtkASMSimplify.h"
#include "vtkNew.h"

#include <gtest/gtest.h>

using namespace asmbench;

TEST(BenchmarkSettings, PropertiesAreSetByName)
{
  vtkNew<vtkASMSimplify> filter;
  std::string error;
  ASSERT_TRUE(ApplyAsmSettings(
    filter, "FillHoles=0,FinalLloydIterations=1,KeyPointRadius=0.5,Mode=paper", error))
    << error;
  EXPECT_EQ(filter->GetFillHoles(), 0);
  EXPECT_EQ(filter->GetFinalLloydIterations(), 1);
  EXPECT_EQ(filter->GetKeyPointRadius(), 0.5);
  EXPECT_EQ(filter->GetMode(), vtkASMSimplify::PAPER);
  ASSERT_TRUE(ApplyAsmSettings(filter, "Mode=feature", error)) << error;
  EXPECT_EQ(filter->GetMode(), vtkASMSimplify::FEATURE_PRESERVING);
  EXPECT_TRUE(ApplyAsmSettings(filter, "", error)); // nothing to set
  // Every name the error message lists is one ApplyAsmSettings accepts.
  EXPECT_NE(AsmSettingNames().find("VariationCap"), std::string::npos);
  EXPECT_NE(AsmSettingNames().find("BoundSnappedHoles"), std::string::npos);
}

TEST(BenchmarkSettings, BadSettingsAreErrorsAndStopThere)
{
  vtkNew<vtkASMSimplify> filter;
  const int lloyd = filter->GetLloydIterations();
  const int finalLloyd = filter->GetFinalLloydIterations();
  const double radius = filter->GetKeyPointRadius();
  std::string error;
  for (const char* bad : { "Nope=1", "FillHoles", "FillHoles=", "=1", "FillHoles=yes", "Mode=fast",
         "FinalLloydIterations=99", "LloydIterations=1.5", "KeyPointRadius=nan" })
  {
    error.clear();
    EXPECT_FALSE(ApplyAsmSettings(filter, std::string(bad) + ",LloydIterations=7", error)) << bad;
    EXPECT_FALSE(error.empty()) << bad;
    EXPECT_EQ(filter->GetLloydIterations(), lloyd) << bad << ": changed by a rejected setting";
    EXPECT_EQ(filter->GetFinalLloydIterations(), finalLloyd) << bad; // (clamped: put back)
    EXPECT_EQ(filter->GetKeyPointRadius(), radius) << bad;
  }
  // A clamped value names what the property holds instead.
  ApplyAsmSettings(filter, "FinalLloydIterations=99", error);
  EXPECT_NE(error.find("holds 8"), std::string::npos) << error;
}

TEST(BenchmarkSettings, VariantsAreParsed)
{
  AsmConfig config;
  std::string error;
  ASSERT_TRUE(ParseAsmVariant("ASM fast:FillHoles=0,FinalLloydIterations=0", config, error))
    << error;
  EXPECT_EQ(config.Name, "ASM fast");
  EXPECT_EQ(config.Settings, "FillHoles=0,FinalLloydIterations=0");
  EXPECT_EQ(config.Mode, AsmMode::FeaturePreserving);
  EXPECT_FALSE(config.Curvature);
  EXPECT_TRUE(config.Variant);
  ASSERT_TRUE(ParseAsmVariant("literal:Mode=paper,Alpha=0.25", config, error)) << error;
  EXPECT_EQ(config.Mode, AsmMode::Paper);
  EXPECT_FALSE(ParseAsmVariant("FillHoles=0", config, error));              // no name
  EXPECT_FALSE(ParseAsmVariant(":FillHoles=0", config, error));             // empty name
  EXPECT_FALSE(ParseAsmVariant("ASM default:FillHoles=0", config, error));  // a standard name
  EXPECT_FALSE(ParseAsmVariant("vtkVoxelGrid:FillHoles=0", config, error)); // a peer's name
  EXPECT_FALSE(ParseAsmVariant("CGAL grid:FillHoles=0", config, error));
  EXPECT_FALSE(ParseAsmVariant("x:FillHoles=maybe", config, error));
  // The programs' --asm: appended once per name.
  std::vector<AsmConfig> configs;
  EXPECT_TRUE(AddAsmVariant("fast:FillHoles=0", configs));
  EXPECT_FALSE(AddAsmVariant("fast:FinalLloydIterations=0", configs));
  EXPECT_FALSE(AddAsmVariant("bad:Nope=1", configs));
  ASSERT_EQ(configs.size(), 1u);
  EXPECT_EQ(configs[0].Settings, "FillHoles=0");
}

TEST(BenchmarkSettings, AVariantRunsWithItsSettingsOnly)
{
  const Input input = MakeInput("bumps:20k");
  ASSERT_TRUE(input.Data);
  const vtkIdType target = 1000;
  const RunResult standard = MakeAsm(input.Data, target, AsmConfigurations().front()).Run(true);
  AsmConfig same, fast;
  std::string error;
  ASSERT_TRUE(ParseAsmVariant("same:", same, error)) << error;
  ASSERT_TRUE(ParseAsmVariant("fast:FillHoles=0,FinalLloydIterations=0", fast, error)) << error;
  const RunResult a = MakeAsm(input.Data, target, same).Run(true);
  const RunResult b = MakeAsm(input.Data, target, fast).Run(true);
  EXPECT_EQ(standard.Count, target);
  EXPECT_EQ(b.Count, target);
  EXPECT_EQ(a.Xyz, standard.Xyz); // no settings: the default mode itself
  EXPECT_NE(b.Xyz, standard.Xyz); // without the hole filling the samples differ
}
