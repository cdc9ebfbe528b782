// A render job is a value that travels to other ranks as it is: every field survives the bytes, and bytes that are
// not a job are refused rather than misread.
#include <gtest/gtest.h>

#include "rayview/frame_plan.h"
#include "rayview/render_job.h"

namespace rayview {
namespace {

RenderJob everyFieldSet() {
  RenderJob job;
  job.scenes = {"a.xml", "models/b.glb", ""};
  job.open.strict = true;
  job.open.camera = 3;
  job.open.model.up = ModelUpAxis::Z;
  job.open.model.width = 321;
  job.open.model.height = 123;
  job.open.model.camera = ModelViewSource::Rayview;
  job.open.model.lights = ModelViewSource::File;
  job.open.memory = MemoryUse::Lean;
  job.open.loadTexture = false;
  job.knobs = {{findKnob("depth"), 7}, {findKnob("light-samples"), 16}, {findKnob("samples"), 4}};
  job.output = "out/spin_%03d.png";
  job.turntableFrames = 12;
  job.overwrite = true;
  job.quiet = true;
  job.threads = 5;
  return job;
}

TEST(RenderJob, EveryFieldSurvivesTheBytes) {
  const RenderJob job = everyFieldSet();
  const RenderJob back = decodeRenderJob(encodeRenderJob(job));
  EXPECT_EQ(back.scenes, job.scenes);
  EXPECT_EQ(back.open.strict, job.open.strict);
  EXPECT_EQ(back.open.camera, job.open.camera);
  EXPECT_EQ(back.open.model.up, job.open.model.up);
  EXPECT_EQ(back.open.model.width, job.open.model.width);
  EXPECT_EQ(back.open.model.height, job.open.model.height);
  EXPECT_EQ(back.open.model.camera, job.open.model.camera);
  EXPECT_EQ(back.open.model.lights, job.open.model.lights);
  EXPECT_EQ(back.open.memory, job.open.memory);
  EXPECT_EQ(back.open.loadTexture, job.open.loadTexture);
  ASSERT_EQ(back.knobs.size(), job.knobs.size());
  for (std::size_t i = 0; i < job.knobs.size(); ++i) {
    EXPECT_EQ(back.knobs[i].knob, job.knobs[i].knob);
    EXPECT_EQ(back.knobs[i].value, job.knobs[i].value);
  }
  EXPECT_EQ(back.output, job.output);
  EXPECT_EQ(back.turntableFrames, job.turntableFrames);
  EXPECT_EQ(back.overwrite, job.overwrite);
  EXPECT_EQ(back.quiet, job.quiet);
  EXPECT_EQ(back.threads, job.threads);
  // A field the codec forgot would show here too: the bytes of the copy are the bytes of the original.
  EXPECT_EQ(encodeRenderJob(back), encodeRenderJob(job));
  EXPECT_NE(encodeRenderJob(RenderJob{}), encodeRenderJob(job));
}

TEST(RenderJob, BytesThatAreNotAJobAreRefused) {
  const std::vector<std::uint8_t> bytes = encodeRenderJob(everyFieldSet());
  for (std::size_t cut = 0; cut < bytes.size(); ++cut)
    EXPECT_THROW(decodeRenderJob(std::vector<std::uint8_t>(bytes.begin(), bytes.begin() + static_cast<long>(cut))),
                 JobCodecError)
        << "cut at " << cut;
  std::vector<std::uint8_t> longer = bytes;
  longer.push_back(0);
  EXPECT_THROW(decodeRenderJob(longer), JobCodecError);
  std::vector<std::uint8_t> foreign = bytes;
  foreign[0] ^= 0xff;
  EXPECT_THROW(decodeRenderJob(foreign), JobCodecError);
}

TEST(FramePlan, TwoInputsThatWouldWriteOneFileAreRefusedNamingBoth) {
  RenderJob job;
  job.scenes = {"a/x.xml", "b/x.xml"};
  job.output = "out/";
  try {
    planFrames(job);
    FAIL() << "planned";
  } catch (const PlanError& error) {
    EXPECT_NE(std::string(error.what()).find("a/x.xml and b/x.xml would both be written to out/x.png"),
              std::string::npos)
        << error.what();
  }
  job.scenes = {"a/x.xml", "b/y.xml"};
  EXPECT_EQ(planFrames(job).size(), 2u);
}

TEST(FramePlan, AFrameOpensItsSceneWithItsCamera) {
  RenderJob job = everyFieldSet();
  const FrameJob frame{"c.ceng477.xml", 2, 0, 0, "dir/view2.png"};
  const RenderJob one = jobForFrame(job, frame);
  EXPECT_EQ(one.scenes, std::vector<std::string>{"c.ceng477.xml"});
  EXPECT_EQ(one.open.camera, 2);
  EXPECT_EQ(one.output, frame.output);
  EXPECT_EQ(one.turntableFrames, 0);
  EXPECT_EQ(one.open.model.width, job.open.model.width) << "the rest as the job has it";
}

}  // namespace
}  // namespace rayview
