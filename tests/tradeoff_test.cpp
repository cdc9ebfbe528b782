// The speed-for-accuracy measurement: image metrics on known images, the knobs enumerated, a small tradeoff
// run (exact at its finest settings), its CSV and its plot.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <sstream>
#include <string>
#include <vector>

#include "rayview/image_metrics.h"
#include "rayview/plot.h"
#include "rayview/tradeoff.h"
#include "support/scene_builder.h"
#include "support/test_meshes.h"

namespace rayview {
namespace {

using testing::addQuadFacingZ;
using testing::addTriangle;
using testing::frontCamera;
using testing::plainMaterial;

Image filled(int w, int h, std::uint8_t value) {
  Image image(w, h);
  std::fill(image.rgb.begin(), image.rgb.end(), value);
  return image;
}

// ---- Metrics

TEST(ImageMetrics, IdenticalImagesAreExact) {
  const Image a = filled(5, 4, 77);
  const ImageError e = compareToReference(a, a);
  EXPECT_EQ(e.rmse, 0.0);
  EXPECT_TRUE(std::isinf(e.psnrDb));
  EXPECT_EQ(e.pctOffByMoreThan1, 0.0);
  EXPECT_EQ(e.maxChannelDifference, 0);
}

TEST(ImageMetrics, UniformOffsetGivesThatRmse) {
  const ImageError e = compareToReference(filled(8, 8, 103), filled(8, 8, 100));
  EXPECT_DOUBLE_EQ(e.rmse, 3.0);
  EXPECT_DOUBLE_EQ(e.psnrDb, 20.0 * std::log10(255.0 / 3.0));
  EXPECT_DOUBLE_EQ(e.pctOffByMoreThan1, 100.0);
  EXPECT_EQ(e.maxChannelDifference, 3);
}

TEST(ImageMetrics, OffByOneIsNotOff) {
  const ImageError e = compareToReference(filled(4, 4, 101), filled(4, 4, 100));
  EXPECT_DOUBLE_EQ(e.rmse, 1.0);
  EXPECT_EQ(e.pctOffByMoreThan1, 0.0);
}

TEST(ImageMetrics, OneChannelOfHalfThePixels) {
  const Image reference = filled(4, 2, 10);
  Image image = reference;
  for (int x = 0; x < 4; ++x) image.pixel(x, 0)[1] = 12;  // the top row's green, off by 2
  const ImageError e = compareToReference(image, reference);
  // 4 channels of 24 off by 2: sqrt(4 * 4 / 24).
  EXPECT_DOUBLE_EQ(e.rmse, std::sqrt(16.0 / 24.0));
  EXPECT_DOUBLE_EQ(e.pctOffByMoreThan1, 50.0);
}

TEST(ImageMetrics, SummaryIsTheLineCompareAndTheViewerPrint) {
  EXPECT_EQ(comparisonSummary(compareToReference(filled(4, 4, 9), filled(4, 4, 9))),
            "exact=100.000% within1=100.000% maxdiff=0 psnr=inf");
  const Image reference = filled(4, 2, 10);
  Image image = reference;
  image.pixel(0, 0)[0] = 11;  // within 1
  image.pixel(1, 0)[2] = 40;  // off by 30
  // 6 of 8 exact, 7 of 8 within 1; rmse sqrt((1 + 900) / 24).
  EXPECT_EQ(comparisonSummary(compareToReference(image, reference)),
            "exact=75.000% within1=87.500% maxdiff=30 psnr=" + formatPsnr(psnrFromRmse(std::sqrt(901.0 / 24.0))));
  EXPECT_EQ(formatPsnr(48.0849), "48.08");
}

TEST(ImageMetrics, DifferenceImageColoursEachPixelByItsLargestChannelDifference) {
  const Image reference = filled(4, 1, 200);
  Image image = reference;
  image.pixel(1, 0)[0] = 201;  // 1
  image.pixel(2, 0)[1] = 192;  // 8
  image.pixel(3, 0)[2] = 0;    // 200
  const Image diff = differenceImage(image, reference);
  auto rgb = [&](int x) { return std::vector<int>(diff.pixel(x, 0), diff.pixel(x, 0) + 3); };
  EXPECT_EQ(rgb(0), (std::vector<int>{50, 50, 50}));  // identical: the reference at a quarter
  EXPECT_EQ(rgb(1), (std::vector<int>{40, 90, 255}));  // blue
  EXPECT_EQ(rgb(2), (std::vector<int>{255, 220, 0}));  // yellow
  EXPECT_EQ(rgb(3), (std::vector<int>{255, 0, 0}));    // red
}

TEST(ImageMetrics, SizesMustMatch) {
  EXPECT_THROW(compareToReference(filled(4, 4, 0), filled(4, 5, 0)), std::invalid_argument);
  EXPECT_TRUE(std::isinf(psnrFromRmse(0.0)));
}

// ---- Scenes

// A lit wall with a small occluder in front (a hard shadow) and a mirror on the right half.
Scene wallScene(bool triangularLight, int size = 40) {
  Scene scene;
  scene.camera = frontCamera(size);
  scene.maxRayDepth = 2;
  scene.background = Color(50, 100, 150);
  scene.materials.push_back(plainMaterial("matte"));
  Material mirror = plainMaterial("mirror");
  mirror.diffuse = Color(0.3f);
  mirror.mirror = Color(0.7f);
  scene.materials.push_back(mirror);
  addQuadFacingZ(scene, -4, -4, 4, 4, -4, 0);
  addQuadFacingZ(scene, 0.8, -4, 4, 4, -3.9, 1);
  addQuadFacingZ(scene, -0.5, -0.5, 0.5, 0.5, -2, 0);
  // Behind the camera, facing it: what the mirror shows.
  addTriangle(scene, {-20, -20, 2}, {20, 20, 2}, {20, -20, 2}, 0);
  addTriangle(scene, {-20, -20, 2}, {-20, 20, 2}, {20, 20, 2}, 0);
  if (triangularLight) {
    // (v1 - v2) x (v1 - v3) points down -z, at the wall.
    scene.lights.of<TriangularLight>().push_back({"tri", {0, 0.6, -1}, {0.6, -0.6, -1}, {-0.6, -0.6, -1}, Color(3000.0f)});
  } else {
    scene.lights.of<PointLight>().push_back({"point", {0.2, 0.3, -1}, Color(3000.0f)});
  }
  return scene;
}

std::vector<KnobSetting> settingsOf(const std::vector<KnobSetting>& all, TradeoffKnob knob) {
  std::vector<KnobSetting> out;
  std::copy_if(all.begin(), all.end(), std::back_inserter(out), [&](const KnobSetting& k) { return k.knob == knob; });
  return out;
}

std::vector<std::string> labelsOf(const std::vector<KnobSetting>& settings) {
  std::vector<std::string> labels;
  for (const KnobSetting& k : settings) labels.push_back(k.label);
  return labels;
}

// ---- Enumeration

TEST(KnobEnumeration, EveryKnobOfASceneWithMirrorsAndATriangularLight) {
  const Scene scene = wallScene(true);
  const std::vector<KnobSetting> all = enumerateKnobSettings(scene, TradeoffOptions{});
  ASSERT_FALSE(all.empty());
  EXPECT_EQ(all.front().knob, TradeoffKnob::BestImage);
  EXPECT_EQ(all.front().settings.accel, AccelKind::Reference);
  EXPECT_EQ(all.front().settings.lightSamples, 256);
  EXPECT_EQ(all.front().depth, 2);
  EXPECT_EQ(labelsOf(settingsOf(all, TradeoffKnob::Preview)),
            (std::vector<std::string>{"1/16", "1/8", "1/4", "1/2", "1"}));
  EXPECT_EQ(labelsOf(settingsOf(all, TradeoffKnob::Depth)), (std::vector<std::string>{"0", "1", "2"}));
  EXPECT_EQ(labelsOf(settingsOf(all, TradeoffKnob::LightSamples)),
            (std::vector<std::string>{"1", "2", "4", "8", "16", "32", "64", "128", "256"}));
  const auto accel = settingsOf(all, TradeoffKnob::Accel);
  ASSERT_FALSE(accel.empty());
  EXPECT_EQ(accel.back().label, "reference");
  // Each knob varies alone: everything else stays at the baseline.
  for (const KnobSetting& k : settingsOf(all, TradeoffKnob::LightSamples)) {
    EXPECT_EQ(k.stride, 1);
    EXPECT_EQ(k.depth, 2);
    EXPECT_EQ(k.settings.accel, availableAccel(AccelKind::Embree));
  }
  for (const KnobSetting& k : settingsOf(all, TradeoffKnob::Preview)) EXPECT_EQ(k.settings.lightSamples, 1);
}

TEST(KnobEnumeration, WithoutMirrorsOrTriangularLights) {
  Scene scene = wallScene(false);
  scene.materials[1].mirror = Color(0.0f);
  scene.maxRayDepth = 5;
  const std::vector<KnobSetting> all = enumerateKnobSettings(scene, TradeoffOptions{});
  EXPECT_EQ(labelsOf(settingsOf(all, TradeoffKnob::Depth)), (std::vector<std::string>{"0", "5"}));
  EXPECT_TRUE(settingsOf(all, TradeoffKnob::LightSamples).empty());
  EXPECT_EQ(all.front().settings.lightSamples, 1);
}

TEST(KnobEnumeration, TheUsersLightModelAndRayStartHoldForEverySetting) {
  TradeoffOptions options;
  options.baseline.triangularLightModel = TriangularLightModel::Directional;
  options.baseline.secondaryRayStart = SecondaryRayStart::ExcludeHitTriangle;
  const std::vector<KnobSetting> all = enumerateKnobSettings(wallScene(true), options);
  for (const KnobSetting& k : all) {
    EXPECT_EQ(k.settings.triangularLightModel, TriangularLightModel::Directional) << k.label;
    EXPECT_EQ(k.settings.secondaryRayStart, SecondaryRayStart::ExcludeHitTriangle) << k.label;
  }
  // Samples only matter for the area model.
  EXPECT_TRUE(settingsOf(all, TradeoffKnob::LightSamples).empty());
}

TEST(KnobEnumeration, EachRowVariesOneKnobFromTheUsersSettings) {
  const Scene scene = wallScene(true);  // depth 2, a mirror, a triangular light
  TradeoffOptions options;
  options.baseline.lightSamples = 6;
  options.baseline.pixelSamples = 3;
  options.baseline.secondaryRayStart = SecondaryRayStart::ExcludeHitTriangle;
  const std::vector<KnobSetting> all = enumerateKnobSettings(scene, options);
  RenderSettings users = options.baseline;
  users.accel = availableAccel(AccelKind::Embree);
  // The user's own values are among each knob's settings.
  EXPECT_EQ(labelsOf(settingsOf(all, TradeoffKnob::LightSamples)),
            (std::vector<std::string>{"1", "2", "4", "6", "8", "16", "32", "64", "128", "256"}));
  EXPECT_EQ(labelsOf(settingsOf(all, TradeoffKnob::PixelSamples)),
            (std::vector<std::string>{"1", "2", "3", "4", "8", "16"}));
  // Every row differs from the user's settings in its own knob only.
  for (const KnobSetting& k : all) {
    if (k.knob == TradeoffKnob::BestImage) continue;
    RenderSettings expected = users;
    if (k.knob == TradeoffKnob::LightSamples) expected.lightSamples = std::stoi(k.label);
    if (k.knob == TradeoffKnob::PixelSamples) expected.pixelSamples = std::stoi(k.label);
    if (k.knob == TradeoffKnob::Accel) expected.accel = k.settings.accel;
    EXPECT_EQ(k.settings, expected) << toString(k.knob) << " " << k.label;
    EXPECT_EQ(k.depth, k.knob == TradeoffKnob::Depth ? std::stoi(k.label) : 2) << toString(k.knob) << " " << k.label;
    EXPECT_EQ(k.stride, k.knob == TradeoffKnob::Preview ? k.stride : 1);
  }
  // The best image improves the user's settings and keeps their samples per pixel.
  const KnobSetting& best = all.front();
  EXPECT_EQ(best.settings.lightSamples, 256);
  EXPECT_EQ(best.settings.accel, AccelKind::Reference);
  EXPECT_EQ(best.settings.pixelSamples, 3);
  EXPECT_EQ(best.settings.secondaryRayStart, SecondaryRayStart::ExcludeHitTriangle);
  EXPECT_EQ(best.depth, 2);
  options.baseline.lightSamples = 1000;  // more than the best image's usual count: the best image has as many
  EXPECT_EQ(enumerateKnobSettings(scene, options).front().settings.lightSamples, 1000);
}

TEST(KnobEnumeration, DeepScenesListPowersOfTwo) {
  Scene scene = wallScene(false);
  scene.maxRayDepth = 40;
  TradeoffOptions options;
  options.limit(lightSamplesKnob(), 6);
  EXPECT_EQ(labelsOf(settingsOf(enumerateKnobSettings(scene, options), TradeoffKnob::Depth)),
            (std::vector<std::string>{"0", "1", "2", "4", "8", "16", "32", "40"}));
  scene = wallScene(true);
  EXPECT_EQ(labelsOf(settingsOf(enumerateKnobSettings(scene, options), TradeoffKnob::LightSamples)),
            (std::vector<std::string>{"1", "2", "4", "6"}));
}

// ---- Measuring

// The scene's own parameters on its own geometry, as `rayview bench tradeoff` measures a file.
TradeoffReport measureScene(const Scene& scene, const TradeoffOptions& options, ThreadPool& pool,
                            const std::atomic<bool>* cancel = nullptr, const TradeoffProgressFn& progress = {}) {
  const std::string name = scene.sourcePath.empty() ? "default" : scene.sourcePath.stem().string();
  return measureTradeoff(scene, std::make_shared<const SceneGeometry>(scene.geometry()), name, options, pool, cancel,
                         progress);
}

const TradeoffPoint& pointOf(const TradeoffReport& report, TradeoffKnob knob, const std::string& label) {
  for (const TradeoffPoint& p : report.points)
    if (p.setting.knob == knob && p.setting.label == label) return p;
  throw std::runtime_error("no point " + std::string(toString(knob)) + " " + label);
}

TradeoffOptions quickOptions() {
  TradeoffOptions options;
  options.timedRuns = 1;
  options.fastTimedRuns = 1;
  options.baseline.accel = AccelKind::Reference;  // so the finest setting of each knob is the reference image
  return options;
}

TEST(MeasureTradeoff, PreviewErrorFallsToZeroAtFullResolution) {
  ThreadPool pool(2);
  const TradeoffReport report = measureScene((wallScene(false)), quickOptions(), pool);
  ASSERT_FALSE(report.cancelled);
  EXPECT_EQ(report.width, 40);
  EXPECT_EQ(report.threads, 2);

  const TradeoffPoint& reference = report.points.front();
  EXPECT_EQ(reference.setting.knob, TradeoffKnob::BestImage);
  EXPECT_EQ(reference.error.rmse, 0.0);

  std::vector<double> previewRmse;
  for (const char* label : {"1/16", "1/8", "1/4", "1/2", "1"})
    previewRmse.push_back(pointOf(report, TradeoffKnob::Preview, label).error.rmse);
  EXPECT_EQ(previewRmse.back(), 0.0);
  EXPECT_GT(previewRmse.front(), 1.0);
  // Monotone-ish: each level no worse than the coarsest, and refining two levels always helps.
  for (std::size_t i = 0; i < previewRmse.size(); ++i) EXPECT_LE(previewRmse[i], previewRmse.front()) << i;
  for (std::size_t i = 0; i + 2 < previewRmse.size(); ++i) EXPECT_LT(previewRmse[i + 2], previewRmse[i]) << i;
  // Fewer pixels, fewer rays: the camera rays of a 1/s preview are its grid.
  EXPECT_LT(pointOf(report, TradeoffKnob::Preview, "1/16").rays, pointOf(report, TradeoffKnob::Preview, "1").rays);

  // Depth: the mirror needs one bounce; the scene's maximum is exact.
  EXPECT_GT(pointOf(report, TradeoffKnob::Depth, "0").error.rmse, 1.0);
  EXPECT_EQ(pointOf(report, TradeoffKnob::Depth, "1").error.rmse, 0.0);
  EXPECT_EQ(pointOf(report, TradeoffKnob::Depth, "2").error.rmse, 0.0);

  // Settings that coincide are one render: same time, same figures.
  const TradeoffPoint& fullPreview = pointOf(report, TradeoffKnob::Preview, "1");
  const TradeoffPoint& maxDepth = pointOf(report, TradeoffKnob::Depth, "2");
  EXPECT_EQ(fullPreview.timeMs, maxDepth.timeMs);
  EXPECT_EQ(fullPreview.rays, maxDepth.rays);
  for (const TradeoffPoint& p : report.points) {
    EXPECT_GT(p.timeMs, 0.0);
    EXPECT_EQ(p.runs, 1);
  }
}

// A sphere of 81 920 triangles filling most of a 200 x 150 image: big enough that a pass costs more the more
// pixels it traces, as the user's scenes do, while each preview level stays well under a millisecond.
Scene manyTriangles() {
  Scene scene;
  scene.camera = frontCamera(200);
  scene.camera.height = 150;
  scene.camera.bottom = -0.75;
  scene.camera.top = 0.75;
  scene.materials.push_back(plainMaterial("matte"));
  testing::Placement placement;
  placement.centre = {0.0, 0.0, -2.5};
  placement.size = 1.6;
  testing::addIcosphere(scene, placement, 6, 0);
  scene.lights.of<PointLight>().push_back({"point", {1.0, 2.0, 0.0}, Color(4000.0f)});
  return scene;
}

// Its cost is the rays it casts (its time is bench/'s to measure).
TEST(MeasureTradeoff, ACoarserPreviewLevelCastsFewerRaysThanAFinerOne) {
  ThreadPool pool(2);
  TradeoffOptions options;  // the repetitions the user's measurement makes
  options.slowedRetries = 1;  // as the viewer: a busy machine slows the long renders, not this test's subject
  options.limit(pixelSamplesKnob(), 1);
  const TradeoffReport report = measureScene(manyTriangles(), options, pool);
  ASSERT_FALSE(report.cancelled);
  const char* const levels[] = {"1/16", "1/8", "1/4", "1/2", "1"};
  for (std::size_t i = 0; i + 1 < std::size(levels); ++i) {
    const TradeoffPoint& coarser = pointOf(report, TradeoffKnob::Preview, levels[i]);
    const TradeoffPoint& finer = pointOf(report, TradeoffKnob::Preview, levels[i + 1]);
    EXPECT_LT(coarser.rays, finer.rays) << levels[i];
  }
}

TEST(MeasureTradeoff, TheBaselineIsTheUsersSettingsAndTheReportSaysWhichInThePanelsWords) {
  ThreadPool pool(2);
  TradeoffOptions options = quickOptions();
  options.baseline.accel = availableAccel(AccelKind::Embree);
  options.baseline.lightSamples = 4;
  options.baseline.pixelSamples = 2;
  options.limit(lightSamplesKnob(), 8, 8);
  options.limit(pixelSamplesKnob(), 4);
  const TradeoffReport report = measureScene(wallScene(true, 16), options, pool);
  ASSERT_FALSE(report.cancelled);
  EXPECT_EQ(report.baseline.settings.lightSamples, 4);
  EXPECT_EQ(report.baseline.settings.pixelSamples, 2);
  EXPECT_EQ(report.baseline.depth, 2);
  // The full-resolution preview, 4 light samples and 2 samples per pixel are that one render.
  const TradeoffPoint& full = pointOf(report, TradeoffKnob::Preview, "1");
  EXPECT_EQ(full.rays, pointOf(report, TradeoffKnob::LightSamples, "4").rays);
  EXPECT_EQ(full.rays, pointOf(report, TradeoffKnob::PixelSamples, "2").rays);
  EXPECT_EQ(full.timeMs, pointOf(report, TradeoffKnob::LightSamples, "4").timeMs);
  EXPECT_GT(full.rays, pointOf(report, TradeoffKnob::PixelSamples, "1").rays);
  const std::string traversal = availableAccel(AccelKind::Embree) == AccelKind::Embree ? "Embree" : "packet BVH";
  EXPECT_EQ(report.baselineText, "Max ray depth 2, Tri-light model area, Light samples 4, Traversal " + traversal +
                                     ", Ray start offset off the surface, Samples per pixel 2, Quantisation round to nearest");
  EXPECT_EQ(report.bestText, "Max ray depth 2, Tri-light model area, Light samples 8, Traversal reference BVH, Ray "
                             "start offset off the surface, Samples per pixel 2, Quantisation round to nearest");
}

TEST(MeasureTradeoff, LightSamplesConvergeToTheReference) {
  ThreadPool pool(2);
  TradeoffOptions options = quickOptions();
  options.limit(lightSamplesKnob(), 64, 64);
  const TradeoffReport report = measureScene((wallScene(true, 24)), options, pool);
  ASSERT_FALSE(report.cancelled);
  EXPECT_GT(pointOf(report, TradeoffKnob::LightSamples, "1").error.rmse, 0.5);
  EXPECT_EQ(pointOf(report, TradeoffKnob::LightSamples, "64").error.rmse, 0.0);
  EXPECT_LT(pointOf(report, TradeoffKnob::LightSamples, "16").error.rmse,
            pointOf(report, TradeoffKnob::LightSamples, "1").error.rmse);
  EXPECT_GT(pointOf(report, TradeoffKnob::LightSamples, "64").rays, pointOf(report, TradeoffKnob::LightSamples, "1").rays);
}

TEST(MeasureTradeoff, EmbreeAgreesWithTheReference) {
  if (availableAccel(AccelKind::Embree) != AccelKind::Embree) GTEST_SKIP() << "built without Embree";
  ThreadPool pool(2);
  TradeoffOptions options;
  options.timedRuns = 3;
  options.fastRunMs = 0.0;
  const TradeoffReport report = measureScene((wallScene(false)), options, pool);
  const TradeoffPoint& embree = pointOf(report, TradeoffKnob::Accel, "embree");
  EXPECT_LT(embree.error.pctOffByMoreThan1, 1.0);
  EXPECT_EQ(pointOf(report, TradeoffKnob::Accel, "reference").error.rmse, 0.0);
  EXPECT_EQ(embree.runs, 3);
  EXPECT_GT(report.buildMs[static_cast<int>(AccelKind::Embree)], 0.0);
  EXPECT_GT(report.buildMs[static_cast<int>(AccelKind::Reference)], 0.0);
}

// The viewer's Trade-off panel starts from the user's settings, whose traversal may be the packet BVH: it is measured
// from that baseline like any other, and each traversal built says how long its build took.
TEST(MeasureTradeoff, APacketBvhBaselineIsMeasured) {
  ThreadPool pool(2);
  TradeoffOptions options = quickOptions();
  options.baseline.accel = AccelKind::Packet;
  const TradeoffReport report = measureScene((wallScene(false)), options, pool);
  ASSERT_FALSE(report.cancelled);
  EXPECT_EQ(report.baseline.settings.accel, AccelKind::Packet);
  EXPECT_NE(report.baselineText.find("Traversal packet BVH"), std::string::npos) << report.baselineText;
  EXPECT_GT(report.buildMs[static_cast<int>(AccelKind::Packet)], 0.0);
  EXPECT_GT(report.buildMs[static_cast<int>(AccelKind::Reference)], 0.0);
  // The packet BVH gives Embree's answers: its baseline image is as close to the best as Embree's.
  EXPECT_LT(pointOf(report, TradeoffKnob::Preview, "1").error.pctOffByMoreThan1, 1.0);
}

TEST(MeasureTradeoff, ResolutionScale) {
  ThreadPool pool(1);
  TradeoffOptions options = quickOptions();
  options.resolutionScale = 0.25;
  const TradeoffReport report = measureScene((wallScene(false)), options, pool);
  EXPECT_EQ(report.width, 10);
  EXPECT_EQ(report.height, 10);
  EXPECT_EQ(pointOf(report, TradeoffKnob::Preview, "1").rays > 0, true);
}

TEST(MeasureTradeoff, CancelBeforeStart) {
  ThreadPool pool(2);
  const std::atomic<bool> cancel{true};
  int calls = 0;
  const TradeoffReport report = measureScene((wallScene(false)), quickOptions(), pool,
                                                &cancel, [&](const TradeoffProgress&) { ++calls; });
  EXPECT_TRUE(report.cancelled);
  EXPECT_TRUE(report.points.empty());
  EXPECT_LE(calls, 1);
}

TEST(MeasureTradeoff, ProgressCountsEveryRender) {
  ThreadPool pool(2);
  int lastDone = -1, planned = 0, calls = 0;
  std::string lastWhat;
  measureScene((wallScene(false, 8)), quickOptions(), pool, nullptr,
                  [&](const TradeoffProgress& p) {
                    EXPECT_GE(p.rendersDone, lastDone);
                    EXPECT_LT(p.rendersDone, p.rendersPlanned) << p.what;
                    lastDone = p.rendersDone;
                    planned = p.rendersPlanned;
                    lastWhat = p.what;
                    ++calls;
                  });
  EXPECT_GT(planned, 0);
  EXPECT_GE(calls, planned);  // every setting rendered alone once (for its image), then the quick ones together
  // An 8 x 8 image renders in microseconds: every setting is quick, and the last report is their timing in turn.
  const std::size_t number = lastWhat.find(" quick settings, in turn");
  ASSERT_NE(number, std::string::npos) << lastWhat;
  EXPECT_EQ(lastDone + std::stoi(lastWhat.substr(0, number)), planned);
}

// ---- The words users see

TEST(TradeoffWords, TheBestImageIsNeverCalledReferenceAndTheKnobsHaveTheRenderPanelsLabels) {
  const std::vector<KnobSetting> all = enumerateKnobSettings(wallScene(true), TradeoffOptions{});
  EXPECT_EQ(toString(TradeoffKnob::BestImage), "best_image");
  EXPECT_EQ(knobLabel(TradeoffKnob::BestImage), "best image");
  EXPECT_EQ(describeRow(all.front()), "best image");
  // The knob column shows the Render panel's labels (the knob table's), the CSV keeps its names.
  EXPECT_EQ(knobLabel(TradeoffKnob::Preview), "Preview level");
  for (TradeoffKnob knob : {TradeoffKnob::Depth, TradeoffKnob::LightSamples, TradeoffKnob::Accel,
                            TradeoffKnob::PixelSamples}) {
    ASSERT_NE(tableKnob(knob), nullptr);
    EXPECT_EQ(knobLabel(knob), tableKnob(knob)->label);
    EXPECT_EQ(toString(knob), tableKnob(knob)->csvName());
  }
  EXPECT_EQ(knobLabel(TradeoffKnob::Depth), "Max ray depth");
  EXPECT_EQ(knobLabel(TradeoffKnob::LightSamples), "Light samples");
  EXPECT_EQ(knobLabel(TradeoffKnob::Accel), "Traversal");
  EXPECT_EQ(knobLabel(TradeoffKnob::PixelSamples), "Samples per pixel");
  std::vector<std::string> rows;
  for (const KnobSetting& k : all) {
    const std::string row = describeRow(k);
    rows.push_back(row);
    EXPECT_EQ(row.find('_'), std::string::npos) << row;  // no snake_case
    // "reference" only ever names the traversal back-end, by its panel label.
    const std::size_t reference = row.find("reference");
    EXPECT_TRUE(reference == std::string::npos || row.substr(reference) == "reference BVH") << row;
  }
  const auto has = [&](const std::string& row) { return std::find(rows.begin(), rows.end(), row) != rows.end(); };
  EXPECT_TRUE(has("Preview level 1/16"));
  EXPECT_TRUE(has("Max ray depth 2"));
  EXPECT_TRUE(has("Light samples 64"));
  EXPECT_TRUE(has("Traversal reference BVH"));
  EXPECT_TRUE(has("Samples per pixel 4"));
  // The fast traversal this build has: Embree, or the packet BVH in its place.
  EXPECT_TRUE(has(availableAccel(AccelKind::Embree) == AccelKind::Embree ? "Traversal Embree" : "Traversal packet BVH"));
}

// ---- CSV and plot

TEST(TradeoffCsv, HeaderAndARowPerSetting) {
  ThreadPool pool(2);
  const TradeoffReport report =
      measureScene((wallScene(true, 16)), quickOptions(), pool);
  EXPECT_EQ(tradeoffCsvHeader(), "scene,knob,setting,time_ms,rmse,psnr_db,pct_off_by_more_than_1,rays\n");
  std::istringstream rows(tradeoffCsvRows(report));
  std::string line;
  std::size_t count = 0;
  while (std::getline(rows, line)) {
    EXPECT_EQ(std::count(line.begin(), line.end(), ','), 7) << line;
    if (count == 0) {
      EXPECT_EQ(line.rfind("default,best_image,depth=2 light_samples=256 accel=reference samples=1,", 0), 0u) << line;
      EXPECT_NE(line.find(",0.0000,inf,0.0000,"), std::string::npos) << line;
    }
    ++count;
  }
  EXPECT_EQ(count, report.points.size());
  EXPECT_EQ(count, enumerateKnobSettings(wallScene(true, 16), quickOptions()).size());
}

TEST(TradeoffPlot, DrawsEverySeries) {
  ThreadPool pool(2);
  const TradeoffReport report =
      measureScene((wallScene(true, 16)), quickOptions(), pool);
  const Image plot = plotTradeoff(report, 640, 400);
  ASSERT_EQ(plot.width, 640);
  ASSERT_EQ(plot.height, 400);
  const auto has = [&](std::uint8_t r, std::uint8_t g, std::uint8_t b) {
    for (std::size_t i = 0; i < plot.rgb.size(); i += 3)
      if (plot.rgb[i] == r && plot.rgb[i + 1] == g && plot.rgb[i + 2] == b) return true;
    return false;
  };
  EXPECT_TRUE(has(0, 114, 178));   // preview
  EXPECT_TRUE(has(213, 94, 0));    // depth
  EXPECT_TRUE(has(0, 158, 115));   // light samples
  EXPECT_TRUE(has(204, 121, 167)); // accel

  TradeoffReport empty;
  empty.cancelled = true;
  EXPECT_EQ(plotTradeoff(empty, 500, 300).width, 500);
}

}  // namespace
}  // namespace rayview

namespace rayview {
namespace {

TEST(KnobEnumeration, SamplesPerPixelGoInPowersOfTwoAgainstTheOneSampleReference) {
  TradeoffOptions options;
  options.limit(pixelSamplesKnob(), 12);
  const std::vector<KnobSetting> all = enumerateKnobSettings(wallScene(false), options);
  std::vector<std::string> labels;
  for (const KnobSetting& k : all)
    if (k.knob == TradeoffKnob::PixelSamples) {
      labels.push_back(k.label);
      EXPECT_EQ(k.settings.pixelSamples, std::stoi(k.label));
    }
  EXPECT_EQ(labels, (std::vector<std::string>{"1", "2", "4", "8", "12"}));
  EXPECT_EQ(all.front().settings.pixelSamples, 1) << "the reference image is the course's one-sample image";
  EXPECT_EQ(toString(TradeoffKnob::PixelSamples), "samples");
}

}  // namespace
}  // namespace rayview
