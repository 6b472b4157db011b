// ShadowPort RHI: everything a D3D11 port needs, in one include.
#pragma once
#include <sp/rhi/common.h>
#include <sp/rhi/context.h>
#include <sp/rhi/device.h>
#include <sp/rhi/format.h>
#include <sp/rhi/helpers.h>
#include <sp/rhi/query.h>
#include <sp/rhi/resource.h>
#include <sp/rhi/shader.h>
#include <sp/rhi/state.h>
#include <sp/rhi/swapchain.h>
#include <sp/rhi/view.h>
#include <sp/hlsl/compiler.h>
