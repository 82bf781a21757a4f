#include "ffdkit/scenes/widget_file.h"

#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <numbers>
#include <sstream>

#include <gtest/gtest.h>

#include "ffdkit/widgets/thesis_examples.h"
#include "scenes_test_support.h"

namespace ffdkit::scenes {
namespace {

using namespace ffdkit::widgets;
namespace fs = std::filesystem;

// From the source root the build defines: __FILE__ is relative when ccache rewrites paths.
const fs::path kWidgetExamples = fs::path(FFDKIT_SOURCE_DIR) / "widgets" / "examples";

std::string fileBytes(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

WidgetModel fromText(const std::string& text, const std::string& name = "tool.json") {
  std::istringstream in(text);
  return readWidgetFile(in, name);
}

std::string widgetErrorOf(const std::string& text) {
  try {
    fromText(text);
  } catch (const WidgetFileError& e) {
    return e.what();
  }
  ADD_FAILURE() << "expected a WidgetFileError";
  return {};
}

// The sample widget files, each with the model it must reproduce.
std::vector<std::pair<std::string, WidgetModel>> examples() {
  Fig62 fig62 = buildFig62();
  fig62.model.applyVariation(fig62.faceRotate, 5.0 * std::numbers::pi / 180.0);
  fig62.model.applyVariation(fig62.edgeTranslate, 0.5);
  fig62.model.applyVariation(fig62.pointTranslate, 0.25);
  return {{"fig6-2.json", fig62.model},
          {"fig6-8.json", buildFig68().model},
          {"fig6-9.json", buildFig69().model},
          {"fig6-10-press.json", buildFig610(0.1, VariationRange{0.0, 0.15}).model}};
}

// FFDKIT_WRITE_WIDGET_EXAMPLES=1 regenerates widgets/examples/ from the builders.
TEST(WidgetFile, ExamplesAreTheCanonicalTextOfTheThesisTools) {
  const bool regenerate = std::getenv("FFDKIT_WRITE_WIDGET_EXAMPLES") != nullptr;
  for (const auto& [file, model] : examples()) {
    if (regenerate) writeWidgetFile(kWidgetExamples / file, model);
    EXPECT_EQ(fileBytes(kWidgetExamples / file), widgetFileText(model)) << file;
  }
}

TEST(WidgetFile, EverySampleRoundTripsToTheSameBytesAndControlPoints) {
  std::size_t count = 0;
  for (const auto& entry : fs::directory_iterator(kWidgetExamples)) {
    if (entry.path().extension() != ".json") continue;
    ++count;
    const std::string bytes = fileBytes(entry.path());
    const WidgetModel model = readWidgetFile(entry.path());
    EXPECT_EQ(widgetFileText(model), bytes) << entry.path();
    const WidgetModel again = fromText(widgetFileText(model));
    for (WidgetId l : model.widgets(WidgetType::Lattice)) EXPECT_EQ(again.worldControlPoints(l), model.worldControlPoints(l));
  }
  EXPECT_GE(count, 4u);
}

TEST(WidgetFile, LoadingReproducesTheControlPointsAndTheTool) {
  for (const auto& [file, built] : examples()) {
    const WidgetModel loaded = readWidgetFile(kWidgetExamples / file);
    for (WidgetId l : built.widgets(WidgetType::Lattice)) {
      EXPECT_EQ(loaded.controlPoints(l), built.controlPoints(l)) << file;
      EXPECT_TRUE(loaded.latticeFrame(l).isApprox(built.latticeFrame(l), 0.0)) << file;
    }
    for (WidgetId a : built.widgets(WidgetType::Affine)) EXPECT_EQ(loaded.variation(a), built.variation(a)) << file;
  }
  // The loaded press works like the built one: one turn, then the clamp.
  WidgetModel press = readWidgetFile(kWidgetExamples / "fig6-10-press.json");
  press.applyVariation(press.find("handle"), 2.0 * std::numbers::pi);
  EXPECT_NEAR(press.variation(press.find("press")), 0.1, 1e-15);
  press.applyVariation(press.find("handle"), 4.0 * std::numbers::pi);
  EXPECT_NEAR(press.variation(press.find("press")), 0.15, 1e-15);
}

TEST(WidgetFile, DeformedModelsRoundTrip) {
  Fig69 fig = buildFig69();
  fig.model.applyVariation(fig.faceLift, 0.3);
  fig.model.applyVariation(fig.childEdge, 0.07);
  fig.model.setSiblingPosition(fig.child, 0);
  const std::string text = widgetFileText(fig.model);
  const WidgetModel loaded = fromText(text);
  EXPECT_EQ(widgetFileText(loaded), text);
  EXPECT_EQ(loaded.worldControlPoints(fig.child), fig.model.worldControlPoints(fig.child));
  EXPECT_EQ(loaded.pipelineOrder(), fig.model.pipelineOrder());
}

TEST(WidgetFile, PathOverloadsWriteAtomically) {
  const fs::path dir = fs::temp_directory_path() / ("ffdkit_widget_file_test_" + std::to_string(std::chrono::steady_clock::now().time_since_epoch().count()));
  fs::create_directories(dir);
  const Fig610 fig = buildFig610();
  writeWidgetFile(dir / "press.json", fig.model);
  EXPECT_EQ(fileBytes(dir / "press.json"), widgetFileText(fig.model));
  std::size_t files = 0;
  for ([[maybe_unused]] const auto& e : fs::directory_iterator(dir)) ++files;
  EXPECT_EQ(files, 1u);  // no temporary left behind
  EXPECT_THROW(writeWidgetFile(dir / "missing" / "press.json", fig.model), WidgetFileError);
  EXPECT_THROW(readWidgetFile(dir / "absent.json"), WidgetFileError);
  fs::remove_all(dir);
}

TEST(WidgetFile, MalformedAndFutureFilesGiveLocatedErrors) {
  std::string e = widgetErrorOf("{\n  \"format\": \"ffdkit-widgets\",\n  \"version\": 1,\n  \"lattices\": [,]\n}\n");
  EXPECT_NE(e.find("tool.json:4:16: syntax error"), std::string::npos) << e;
  e = widgetErrorOf(R"({"format": "ffdkit-widgets", "version": 3})");
  EXPECT_NE(e.find("tool.json /version: widget file version 3 is newer"), std::string::npos) << e;
  e = widgetErrorOf(R"({"format": "ffdkit-widgets"})");
  EXPECT_NE(e.find("/: missing key 'version'"), std::string::npos) << e;
  e = widgetErrorOf(R"({"format": "something", "version": 1})");
  EXPECT_NE(e.find("/format: expected 'ffdkit-widgets'"), std::string::npos) << e;
  e = widgetErrorOf(R"({"format": "ffdkit-widgets", "version": 1, "lattices": [{"id": "w0", "name": "a", "counts": [2, 2, 2], "colour": 1}]})");
  EXPECT_NE(e.find("/lattices/0/colour: unknown key 'colour'"), std::string::npos) << e;
  e = widgetErrorOf(R"({"format": "ffdkit-widgets", "version": 1, "lattices": [{"id": "w0", "name": "a", "counts": [1, 2, 2]}]})");
  EXPECT_NE(e.find("/lattices/0/counts"), std::string::npos) << e;
}

TEST(WidgetFile, BadReferencesRulesAndLoopsAreRefused) {
  const std::string head = R"({"format": "ffdkit-widgets", "version": 1,
    "lattices": [{"id": "w0", "name": "box", "counts": [2, 2, 2]}],
    "cells": [{"id": "w1", "name": "top", "lattice": "w0", "kind": "face", "base": [0, 0, 1], "axis": 2},
              {"id": "w2", "name": "bottom", "lattice": "w0", "kind": "face", "base": [0, 0, 0], "axis": 2}],
    "affines": [{"id": "w3", "name": "a", "kind": "translate"}, {"id": "w4", "name": "b", "kind": "translate"},
                {"id": "w5", "name": "c", "kind": "rotate"}],
    "bindings": [)";
  auto with = [&](const std::string& bindings) { return widgetErrorOf(head + bindings + "]}"); };
  std::string e = with(R"({"id": "b0", "kind": "attachment", "from": "w1", "to": "w9", "mask": "TR"})");
  EXPECT_NE(e.find("/bindings/0/to: unknown widget 'w9' (known: w0, w1, w2, w3, w4, w5)"), std::string::npos) << e;
  e = with(R"({"id": "b0", "kind": "variation", "from": "w3", "to": "w4", "gain": 0})");
  EXPECT_NE(e.find("/bindings/0: conversion gain must be finite and non-zero"), std::string::npos) << e;
  e = with(R"({"id": "b0", "kind": "variation", "from": "w3", "to": "w3"})");
  EXPECT_NE(e.find("itself"), std::string::npos) << e;
  e = with(R"({"id": "b0", "kind": "variation", "from": "w3", "to": "w4", "gain": -1},
              {"id": "b1", "kind": "variation", "from": "w4", "to": "w5", "gain": 1},
              {"id": "b2", "kind": "variation", "from": "w5", "to": "w3", "gain": 1})");
  EXPECT_NE(e.find("/bindings/2: binding 'c' (w5) <-> 'a' (w3) closes the loop w5 -> w3 -> w4 -> w5"), std::string::npos) << e;
  e = with(R"({"id": "b0", "kind": "cell-motion", "from": "w1", "to": "w3", "mask": "TR"})");
  EXPECT_NE(e.find("/bindings/0: binding kind 'cell-motion'"), std::string::npos) << e;
  e = with(R"({"id": "b0", "kind": "attachment", "from": "w1", "to": "w3", "mask": "TX"})");
  EXPECT_NE(e.find("/bindings/0/mask: unknown mask 'TX'"), std::string::npos) << e;
  // And a good one loads.
  EXPECT_NO_THROW(fromText(head + R"({"id": "b0", "kind": "attachment", "from": "w1", "to": "w3", "mask": "TR"}]})"));
}

}  // namespace
}  // namespace ffdkit::scenes
