// Matrix packing as fxc's -Zpr / -Zpc set it, and explicit qualifiers that override both.
// fxc's offsets: n is 60 bytes row_major (4 rows of float3), 48 column_major (3 columns of
// float4), so tail lands at 124 with -Zpr and at 112 without.
cbuffer Params : register(b0) {
  float4x4 m;
  float4x3 n;
  float tail;
  column_major float4x3 c;
  row_major float3x4 r;
};
RWStructuredBuffer<float4> result : register(u0);

[numthreads(1, 1, 1)] void main() {
  float4 v = float4(1, 2, 3, 4);
  result[0] = mul(v, m);
  result[1] = float4(mul(v, n), tail);
  result[2] = float4(mul(v, c), 0);
  result[3] = mul(float3(1, 2, 3), r);
  result[4] = m[1];
  result[5] = float4(n[2], 0);
}
