// Included in the middle of a pass by include-in-pass.fx.
        SetPixelShader(CompileShader(ps_5_0, PS()));
