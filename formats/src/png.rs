//! PNG encoding of the report's pictures.

/// PNG bytes of an RGB image.
pub fn encode(img: &image::RgbImage) -> Result<Vec<u8>, String> {
    let mut png = Vec::new();
    img.write_to(&mut std::io::Cursor::new(&mut png), image::ImageFormat::Png)
        .map_err(|e| e.to_string())?;
    Ok(png)
}
