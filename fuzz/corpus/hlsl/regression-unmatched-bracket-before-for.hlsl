// glslang warns about the unknown attribute (fxc: X3554); with -WX that fails the compile.
float4 main(float4 p : POSITION) : SV_Positionribute] for (int i = 0; i < 2; ++i) p += 1;
  re 2; ++i) p += 1;
  return p;
}
}
}
}
}
}
