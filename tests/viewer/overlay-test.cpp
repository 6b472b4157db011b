// The viewer's overlay pictures (samples/viewer/ui/overlay.h), CPU only: layer tints, the layer
// colour composition from synthetic lab buffers, the shadow-map tiling, overlay names. Expected
// values are written out from the rules in overlay.h / docs/viewer.md, not taken from a run.
#include <gtest/gtest.h>

#include <set>

#include "overlay.h"

namespace sp::test {
namespace {

using viewer::MapImage;

TEST(ViewerOverlay, LayerTintsAreDocumentedAndDistinct) {
  // docs/viewer.md's table.
  const std::array<uint8_t, 3> docs[8] = {{230, 40, 40},  {40, 200, 40},  {50, 90, 240}, {230, 220, 40},
                                          {220, 50, 220}, {40, 210, 220}, {250, 140, 20}, {140, 70, 220}};
  std::set<std::array<uint8_t, 3>> seen;
  for (int k = 0; k < 8; ++k) {
    EXPECT_EQ(viewer::LayerTint(k), docs[k]) << "layer " << k;
    seen.insert(viewer::LayerTint(k));
  }
  EXPECT_EQ(seen.size(), 8u);
  EXPECT_EQ(viewer::LayerTint(8), docs[0]) << "tints repeat every 8 layers";
  EXPECT_EQ(viewer::LayerTint(13), docs[5]);
}

// A 4x2 frame: sky, a pixel that read no map, and pixels of layers 0, 1, 2, 5 and 9.
tech::LabBuffers SyntheticLab() {
  tech::LabBuffers lab;
  lab.width = 4, lab.height = 2;
  const float layers[8] = {-1, -1, 0, 1, 2, 5, 9, 1.0001f};
  for (size_t i = 0; i < 8; ++i) {
    lab.position.push_back(glm::vec4(0, 0, 0, i == 0 ? 0.0f : 1.0f));  // pixel 0: sky
    lab.normal.push_back(glm::vec4(0, 1, 0, 0.5f));
    lab.visibility.push_back(1.0f);
    lab.lookup.push_back(glm::vec4(i == 0 ? 3.0f : layers[i], 0, 0, 1));  // sky's lookup is ignored
    for (uint8_t c : {uint8_t(10 + i), uint8_t(100 + i), uint8_t(255 - i), uint8_t(17)}) lab.color.push_back(c);
  }
  return lab;
}

TEST(ViewerOverlay, LayerColoursTintThePixelsOfEachLayer) {
  tech::LabBuffers lab = SyntheticLab();
  std::vector<uint8_t> out = viewer::ComposeLayerColours(lab);
  ASSERT_EQ(out.size(), lab.color.size());
  const int expectLayer[8] = {-1, -1, 0, 1, 2, 5, 9, 1};
  for (size_t i = 0; i < 8; ++i) {
    EXPECT_EQ(viewer::LayerOf(lab, i), expectLayer[i]) << "pixel " << i;
    EXPECT_EQ(out[i * 4 + 3], 255) << "pixel " << i << ": opaque";
    for (int c = 0; c < 3; ++c) {
      int colour = lab.color[i * 4 + size_t(c)];
      int want = colour;
      if (expectLayer[i] >= 0) want = (colour + viewer::LayerTint(expectLayer[i])[size_t(c)]) / 2;
      EXPECT_EQ(int(out[i * 4 + size_t(c)]), want) << "pixel " << i << " channel " << c;
    }
  }
  // Pixel 2 (layer 0, colour 12,102,253) by hand: ((12+230)/2, (102+40)/2, (253+40)/2).
  EXPECT_EQ(out[8], 121);
  EXPECT_EQ(out[9], 71);
  EXPECT_EQ(out[10], 146);
}

TEST(ViewerOverlay, ShadowMapLayersAreTiledAsScaledGrey) {
  // Two 2x2 layers into 8x4: a 2x1 grid of 4x4 cells, each texel 2x2 pixels.
  MapImage m;
  m.width = 2, m.height = 2, m.layers = 2;
  m.values = {0.25f, 0.5f, 0.75f, 1.0f,  // layer 0: range [0.25, 0.75], 1 = nothing drawn
              0.5f, 0.5f, 0.5f, 0.5f};   // layer 1: flat, so black
  std::vector<uint8_t> out = viewer::TileShadowMap(m, 8, 4);
  ASSERT_EQ(out.size(), 8u * 4 * 4);
  auto grey = [&](uint32_t x, uint32_t y) {
    const uint8_t* p = &out[(size_t(y) * 8 + x) * 4];
    EXPECT_TRUE(p[0] == p[1] && p[1] == p[2] && p[3] == 255) << x << "," << y;
    return int(p[0]);
  };
  EXPECT_EQ(grey(0, 0), 0);
  EXPECT_EQ(grey(1, 1), 0);
  EXPECT_EQ(grey(2, 0), 128);   // 0.5 in [0.25, 0.75]: 127.5 rounds to 128
  EXPECT_EQ(grey(0, 3), 255);   // 0.75: the farthest drawn texel
  EXPECT_EQ(grey(3, 3), 255);   // 1.0: white
  for (uint32_t y = 0; y < 4; ++y)
    for (uint32_t x = 4; x < 8; ++x) EXPECT_EQ(grey(x, y), 0) << "layer 1 " << x << "," << y;

  // Three layers: a 2x2 grid, the fourth cell black; a map wider than its cell is scaled down.
  MapImage wide;
  wide.width = 4, wide.height = 1, wide.layers = 3;
  wide.values.assign(12, 0.0f);
  for (int l = 0; l < 3; ++l) wide.values[size_t(l) * 4 + 3] = 0.5f;  // last texel the farthest
  out = viewer::TileShadowMap(wide, 8, 8);                                // cells 4x4, tile 4x1
  EXPECT_EQ(grey(3, 0), 255);
  EXPECT_EQ(grey(7, 0), 255);
  EXPECT_EQ(grey(3, 4), 255);
  EXPECT_EQ(grey(7, 4), 0) << "no fourth layer";
  EXPECT_EQ(grey(3, 1), 0) << "below the one-texel-high tile";

  // A moment map (not depth): values above 1 are part of the range, not "nothing drawn".
  MapImage moments;
  moments.width = 2, moments.height = 1, moments.layers = 1, moments.depth = false;
  moments.values = {1.0f, 3.0f};  // an exponential moment: exp(c z) >= 1
  out = viewer::TileShadowMap(moments, 8, 4);  // one 8x4 cell: each texel 4x4 pixels
  EXPECT_EQ(grey(3, 3), 0);
  EXPECT_EQ(grey(4, 0), 255);
  EXPECT_EQ(grey(7, 3), 255);
  // Exponential moments over four orders of magnitude: a log scale; the largest is "nothing drawn".
  moments.width = 4, moments.values = {1.0f, 10.0f, 10000.0f, 1e6f};
  out = viewer::TileShadowMap(moments, 8, 2);  // texels 2x2 pixels
  EXPECT_EQ(grey(0, 0), 0);
  EXPECT_EQ(grey(2, 1), 64);  // log 10 a quarter of the way from log 1 to log 10000: 63.75
  EXPECT_EQ(grey(4, 0), 255);
  EXPECT_EQ(grey(6, 1), 255);

  // A picture of the wrong size of values is all black, not a read past the end.
  m.values.pop_back();
  out = viewer::TileShadowMap(m, 8, 4);
  for (uint32_t y = 0; y < 4; ++y)
    for (uint32_t x = 0; x < 8; ++x) EXPECT_EQ(grey(x, y), 0);
}

TEST(ViewerOverlay, NamesRoundTripAndUnknownOnesAreRefused) {
  for (viewer::Overlay o : {viewer::Overlay::Off, viewer::Overlay::Layers, viewer::Overlay::Density, viewer::Overlay::Error,
                            viewer::Overlay::ShadowMap}) {
    viewer::Overlay back = viewer::Overlay::Layers;
    EXPECT_TRUE(viewer::ParseOverlay(viewer::OverlayName(o), &back)) << viewer::OverlayName(o);
    EXPECT_EQ(back, o);
  }
  viewer::Overlay o = viewer::Overlay::Density;
  EXPECT_FALSE(viewer::ParseOverlay("cascades", &o));
  EXPECT_EQ(o, viewer::Overlay::Density) << "untouched";
}

}  // namespace
}  // namespace sp::test
