// -Zpr / -Zpc on the GPU: a compute shader reads cbuffer matrices packed as fxc packs them for
// each flag (tests/hlsl/data/packing.hlsl) and must see D3D11's values on both backends.
#include <fstream>

#include "../rhi/rhi-test-util.h"

namespace sp::test {
namespace {

namespace fs = std::filesystem;

class MatrixPackingTest : public BackendTest {};

struct Mat {
  uint32_t rows, cols;
  std::vector<float> e;  // row by row
  float at(uint32_t r, uint32_t c) const { return e[r * cols + c]; }
};

// A matrix as D3D11 reads it from cbuffer memory: row_major stores row r at register
// offset/16 + r, column_major stores column c at offset/16 + c.
Mat Load(const std::vector<float>& cb, uint32_t offset, uint32_t rows, uint32_t cols, bool rowMajor) {
  Mat m{rows, cols, std::vector<float>(rows * cols)};
  for (uint32_t r = 0; r < rows; ++r)
    for (uint32_t c = 0; c < cols; ++c) m.e[r * cols + c] = cb[offset / 4 + (rowMajor ? r * 4 + c : c * 4 + r)];
  return m;
}

// mul(v, M) with v a row vector.
std::vector<float> Mul(const std::vector<float>& v, const Mat& m) {
  std::vector<float> out(m.cols, 0.0f);
  for (uint32_t c = 0; c < m.cols; ++c)
    for (uint32_t r = 0; r < m.rows; ++r) out[c] += v[r] * m.at(r, c);
  return out;
}

std::vector<float> Pad4(std::vector<float> v, float last = 0.0f) {
  while (v.size() < 3) v.push_back(0.0f);
  if (v.size() == 3) v.push_back(last);
  return v;
}

void RunPacking(Device& dev, DeviceContext& ctx, uint32_t flag, bool rowMajorDefault) {
  fs::path file = fs::path(SHADOWPORT_SHADER_DIR).parent_path() / "tests" / "hlsl" / "data" / "packing.hlsl";
  hlsl::CompileOptions o;
  o.target = "cs_5_0";
  o.flags1 = flag;
  o.cacheDir = fs::path(SHADOWPORT_TEST_OUTPUT_DIR) / "shader-cache";
  ShaderBytecode bc = hlsl::CompileFile(file, o);
  Ref<ComputeShader> cs = dev.CreateComputeShader(bc);

  // Distinct small integers: a misplaced element changes the result, and every product and sum
  // is exact whatever order the GPU adds in.
  std::vector<float> cb(224 / 4);
  for (size_t i = 0; i < cb.size(); ++i) cb[i] = float(int(i) - 28);
  Ref<Buffer> cbuf = MakeBuffer(dev, BIND_CONSTANT_BUFFER, cb.data(), uint32_t(cb.size() * 4));
  UavBuffer out = MakeUavBuffer(dev, 6, 16);
  ctx.CSSetShader(cs.get());
  ctx.CSSetConstantBuffers(0, {cbuf.get()});
  ctx.CSSetUnorderedAccessViews(0, {out.uav.get()});
  ctx.Dispatch(1, 1, 1);
  ctx.CSSetUnorderedAccessViews(0, {nullptr});
  std::vector<float> got = ReadBufferAs<float>(dev, ctx, out.buffer.get());

  // fxc's layout for this flag (checked against reflection in FxcCompat tests).
  uint32_t tailOffset = rowMajorDefault ? 124 : 112;
  Mat m = Load(cb, 0, 4, 4, rowMajorDefault);
  Mat n = Load(cb, 64, 4, 3, rowMajorDefault);
  Mat c = Load(cb, 128, 4, 3, false);
  Mat r = Load(cb, 176, 3, 4, true);
  std::vector<float> v = {1, 2, 3, 4};
  std::vector<std::vector<float>> expect = {
      Mul(v, m),
      Pad4(Mul(v, n), cb[tailOffset / 4]),
      Pad4(Mul(v, c)),
      Mul({1, 2, 3}, r),
      {m.at(1, 0), m.at(1, 1), m.at(1, 2), m.at(1, 3)},
      {n.at(2, 0), n.at(2, 1), n.at(2, 2), 0.0f},
  };
  for (size_t i = 0; i < expect.size(); ++i)
    for (size_t k = 0; k < 4; ++k) EXPECT_EQ(got[i * 4 + k], expect[i][k]) << "result[" << i << "]." << "xyzw"[k];
}

TEST_P(MatrixPackingTest, RowMajorFlagPacksCbufferMatricesAsD3D11) {
  RunPacking(device(), ctx(), hlsl::COMPILE_PACK_MATRIX_ROW_MAJOR, true);
}

TEST_P(MatrixPackingTest, ColumnMajorFlagPacksCbufferMatricesAsD3D11) {
  RunPacking(device(), ctx(), hlsl::COMPILE_PACK_MATRIX_COLUMN_MAJOR, false);
}

SP_INSTANTIATE_BACKEND_TESTS(MatrixPackingTest);

}  // namespace
}  // namespace sp::test
