// D3D11 queries: EVENT, OCCLUSION, TIMESTAMP, TIMESTAMP_DISJOINT.
#pragma once
#include <sp/rhi/common.h>

namespace sp {

enum QUERY : uint32_t {
  QUERY_EVENT = 0,
  QUERY_OCCLUSION = 1,
  QUERY_TIMESTAMP = 2,
  QUERY_TIMESTAMP_DISJOINT = 3,
};

struct QUERY_DESC {
  QUERY Query = QUERY_EVENT;
  uint32_t MiscFlags = 0;
};

// GetData result of a TIMESTAMP_DISJOINT query (D3D11_QUERY_DATA_TIMESTAMP_DISJOINT).
struct QUERY_DATA_TIMESTAMP_DISJOINT {
  uint64_t Frequency = 0;  // ticks per second of TIMESTAMP values
  bool Disjoint = false;
};

enum ASYNC_GETDATA_FLAG : uint32_t { ASYNC_GETDATA_DONOTFLUSH = 0x1 };

class Query : public Object {
 public:
  const QUERY_DESC& GetDesc() const { return desc_; }
  void GetDesc(QUERY_DESC* desc) const { *desc = desc_; }  // D3D11's shape
  const char* TypeName() const override { return "Query"; }
  // Size GetData expects: EVENT bool(4 bytes, BOOL), OCCLUSION uint64, TIMESTAMP uint64,
  // TIMESTAMP_DISJOINT sizeof(QUERY_DATA_TIMESTAMP_DISJOINT).
  uint32_t GetDataSize() const;

 protected:
  friend class Device;
  Query(Device* device, const QUERY_DESC& desc) : Object(device), desc_(desc) {}

 private:
  QUERY_DESC desc_;
};

}  // namespace sp
