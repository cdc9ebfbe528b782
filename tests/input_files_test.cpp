// Nothing a user owns is lost, and every image reader gives the values the file holds or refuses it: the one
// guard against replacing an input (rayview/input_files.h), writes through links with short temporary names,
// and the PNG, JPEG and PPM readers at their edges.
#include <gtest/gtest.h>
#include <unistd.h>

#include <fstream>
#include <string>

#define STB_IMAGE_WRITE_STATIC
#define STB_IMAGE_WRITE_IMPLEMENTATION
#include <stb_image_write.h>

#include "rayview/image.h"
#include "rayview/image_limits.h"
#include "rayview/image_metrics.h"
#include "rayview/input_files.h"
#include "rayview/scene_loader.h"
#include "rayview/scene_source.h"
#include "rayview/scene_writer.h"
#include "rayview/thread_pool.h"
#include "support/image_compare.h"
#include "rayview/texture_image.h"

namespace rayview {
namespace {

namespace fs = std::filesystem;

fs::path freshDirectory(const std::string& name) {
  const fs::path directory = testing::testOutputDirectory() / "input_files" / name;
  fs::remove_all(directory);
  fs::create_directories(directory);
  forgetInputs();
  return directory;
}

void writeBytes(const fs::path& path, const std::string& bytes) {
  std::ofstream(path, std::ios::binary) << bytes;
}

std::string readBytes(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

const char* kTexturedScene = R"(<scene><maxraytracedepth>0</maxraytracedepth><background>0 0 0</background>
<camera><position>0 0 0</position><gaze>0 0 -1</gaze><up>0 1 0</up><nearplane>-1 1 -1 1</nearplane>
<neardistance>1</neardistance><imageresolution>4 4</imageresolution></camera>
<lights><ambientlight>255 255 255</ambientlight></lights>
<materials><material id="1"><ambient>1 1 1</ambient><diffuse>0 0 0</diffuse><specular>0 0 0</specular>
<phongexponent>1</phongexponent></material></materials>
<vertexdata>-1 -1 -2 1 -1 -2 0 1 -2</vertexdata><texturedata>0 0 1 0 0 1</texturedata>
<textureimage>tex.png</textureimage>
<objects><mesh id="1"><materialid>1</materialid><faces>1 2 3</faces></mesh></objects></scene>
)";

Image gradient(int width, int height) {
  Image image(width, height);
  for (std::size_t i = 0; i < image.rgb.size(); ++i) image.rgb[i] = static_cast<std::uint8_t>(i * 37 % 256);
  return image;
}

TEST(InputFiles, ATextureThatDidNotDecodeIsNeverReplaced) {
  const fs::path dir = freshDirectory("texture");
  writeBytes(dir / "scene.xml", kTexturedScene);
  writeBytes(dir / "tex.png", "\x89PNG\r\n\x1a\n but not an image");
  const LoadedScene loaded = loadSceneFile(dir / "scene.xml");
  ASSERT_FALSE(loaded.scene.texture);  // the texture did not load
  fs::create_symlink("tex.png", dir / "link.png");
  for (const fs::path& output : {dir / "tex.png", dir / "." / "tex.png", dir / "link.png"}) {
    EXPECT_NE(outputOverwritesInput(output, (dir / "scene.xml").string(), &loaded.scene).find("texture image"),
              std::string::npos) << output;
    EXPECT_THROW(writeImageFile(output, gradient(2, 2)), ImageIoError) << output;
  }
  EXPECT_EQ(readBytes(dir / "tex.png"), "\x89PNG\r\n\x1a\n but not an image");
  // Saving the scene: never as an image's name, never over the scene itself.
  try {
    writeSceneFile(dir / "edited.png", loaded.scene);
    ADD_FAILURE() << "XML written into a .png";
  } catch (const ImageIoError& error) {
    EXPECT_NE(std::string(error.what()).find("saved as .xml"), std::string::npos) << error.what();
  }
  EXPECT_FALSE(fs::exists(dir / "edited.png"));
  EXPECT_THROW(writeSceneFile(dir / "scene.xml", loaded.scene), ImageIoError);
  EXPECT_NO_THROW(writeSceneFile(dir / "edited.xml", loaded.scene));
}

TEST(InputFiles, AnImageReadIsRefusedAsAnOutputByAnyPath) {
  const fs::path dir = freshDirectory("reference");
  writeImageFile(dir / "ref.png", gradient(3, 2));
  const std::string before = readBytes(dir / "ref.png");
  readImageFile(dir / "ref.png", "the reference image");
  fs::create_hard_link(dir / "ref.png", dir / "hard.png");
  for (const fs::path& output : {dir / "ref.png", dir / ".." / "reference" / "ref.png", dir / "hard.png"}) {
    try {
      writeImageFile(output, gradient(1, 1));
      ADD_FAILURE() << output << " was written";
    } catch (const ImageIoError& error) {
      EXPECT_NE(std::string(error.what()).find("is the reference image"), std::string::npos) << error.what();
    }
  }
  EXPECT_EQ(readBytes(dir / "ref.png"), before);
  // The recent-files list's owner may replace it, and only it.
  writeBytes(dir / "recent.txt", "/a.xml\n");
  detail::readUserFile(dir / "recent.txt", 1 << 20, {}, kRecentFilesRole);
  EXPECT_THROW(writeFileAtomically(dir / "recent.txt", "x"), ImageIoError);
  EXPECT_NO_THROW(writeFileAtomically(dir / "recent.txt", "/b.xml\n", kRecentFilesRole));
  EXPECT_THROW(writeFileAtomically(dir / "ref.png", "x", kRecentFilesRole), ImageIoError);
}

TEST(AtomicWrite, AnyLegalNameWorksAndASymlinkStaysALink) {
  const fs::path dir = freshDirectory("names");
  for (std::size_t length : {5, 200, 241, 250, 255}) {
    const std::string name = std::string(length - 4, 'n') + ".ppm";
    ASSERT_EQ(name.size(), length);
    for (int repeat = 0; repeat < 3; ++repeat) EXPECT_NO_THROW(writeImageFile(dir / name, gradient(2, 2))) << length;
    EXPECT_TRUE(fs::exists(dir / name));
  }
  fs::create_directories(dir / "elsewhere");
  fs::create_symlink("elsewhere/real.txt", dir / "link.txt");
  writeFileAtomically(dir / "link.txt", "through the link\n");
  EXPECT_TRUE(fs::is_symlink(dir / "link.txt"));
  EXPECT_EQ(readBytes(dir / "elsewhere" / "real.txt"), "through the link\n");
  for (const auto& entry : fs::recursive_directory_iterator(dir))
    EXPECT_EQ(entry.path().filename().string().find(".tmp-"), std::string::npos) << entry.path();
}

// --- readers ---

std::optional<Texture> decode(const std::string& bytes, std::string& reason) {
  return detail::decodeImage(bytes, reason);
}

std::string jpegOf(const Image& image) {
  std::string bytes;
  stbi_write_jpg_to_func([](void* context, void* data, int size) {
    static_cast<std::string*>(context)->append(static_cast<const char*>(data), static_cast<std::size_t>(size));
  }, &bytes, image.width, image.height, 3, image.rgb.data(), 95);
  return bytes;
}

TEST(ImageReaders, ATruncatedJpegIsRefused) {
  const std::string whole = jpegOf(gradient(64, 64));
  std::string reason;
  ASSERT_TRUE(decode(whole, reason)) << reason;
  EXPECT_FALSE(decode(whole.substr(0, whole.size() / 2), reason));
  EXPECT_NE(reason.find("cannot be decoded"), std::string::npos) << reason;
}

TEST(ImageReaders, PpmSamplesAreScaledFromTheirMaximumValue) {
  std::string reason;
  const auto white1 = decode(std::string("P6\n2 1\n1\n") + std::string("\1\1\1\0\0\0", 6), reason);
  ASSERT_TRUE(white1) << reason;
  EXPECT_EQ(white1->rgb, (PixelBytes{255, 255, 255, 0, 0, 0}));
  const auto grey16 = decode(std::string("P5\n2 1\n65535\n") + std::string("\xff\xff\x80\x00", 4), reason);
  ASSERT_TRUE(grey16) << reason;
  EXPECT_EQ(grey16->rgb, (PixelBytes{255, 255, 255, 128, 128, 128}));
  const auto mid = decode(std::string("P5\n3 1\n4\n") + std::string("\0\2\4", 3), reason);
  ASSERT_TRUE(mid) << reason;
  EXPECT_EQ(mid->rgb, (PixelBytes{0, 0, 0, 128, 128, 128, 255, 255, 255}));
  EXPECT_FALSE(decode(std::string("P5\n1 1\n4\n") + std::string("\5", 1), reason));  // over maxval
}

TEST(ImageReaders, DeclaredSizesAreCheckedAgainstTheOneLimit) {
  std::string reason;
  EXPECT_FALSE(decode("P6\n1 268435456\n255\n", reason));
  EXPECT_NE(reason.find("1 x 268435456 pixels is too large"), std::string::npos) << reason;
  EXPECT_FALSE(decode("P6\n16385 16384\n255\n", reason));
  EXPECT_NE(reason.find("too large"), std::string::npos) << reason;
  EXPECT_EQ(imageSizeProblem(16384, 16384), "");
  EXPECT_EQ(imageSizeProblem(65536, 4096), "");
  EXPECT_NE(imageSizeProblem(1, 268435456), "");
  EXPECT_NE(imageSizeProblem(0, 5), "");
}

TEST(ThreadPool, ATasksExceptionReachesTheCaller) {
  ThreadPool pool(2);
  EXPECT_THROW(pool.parallelFor(100, [](std::size_t i) {
    if (i == 37) throw std::bad_alloc();
  }), std::bad_alloc);
  std::atomic<int> ran{0};
  pool.parallelFor(10, [&](std::size_t) { ++ran; });  // the pool still works
  EXPECT_EQ(ran.load(), 10);
}

TEST(CompareFigures, NeverRoundUpToTheRequirementAndSayWhenTheCameraDiffers) {
  EXPECT_EQ(formatPercent(262143, 262144), "99.999");
  EXPECT_EQ(formatPercent(262144, 262144), "100.000");
  EXPECT_EQ(formatPercent(1, 262144), "0.000");
  EXPECT_EQ(formatPercent(1, 8), "12.500");
  Image image = gradient(512, 512), reference = image;
  reference.rgb[0] = static_cast<std::uint8_t>(reference.rgb[0] ^ 4);
  ImageError error = compareToReference(image, reference);
  EXPECT_EQ(comparisonSummary(error).rfind("exact=99.999% within1=99.999% maxdiff=4 psnr=", 0), 0u)
      << comparisonSummary(error);
  error.cameraMismatch = "the viewer's camera is not the scene file's";
  EXPECT_NE(comparisonSummary(error).find(" camera=differs (the viewer's camera is not the scene file's)"),
            std::string::npos);
}

}  // namespace
}  // namespace rayview
