# Layer: elements. Modules and the objects of the modules each one uses.
MODULES += cfe_element element_library element_types materials plane_elements
$(OBJDIR)/cfe_element.o: $(OBJDIR)/element_types.o $(OBJDIR)/kinds.o $(OBJDIR)/plane_elements.o
$(OBJDIR)/element_library.o: $(OBJDIR)/cfe_element.o $(OBJDIR)/element_types.o $(OBJDIR)/plane_elements.o
$(OBJDIR)/element_types.o: $(OBJDIR)/kinds.o
$(OBJDIR)/materials.o: $(OBJDIR)/kinds.o
$(OBJDIR)/plane_elements.o: $(OBJDIR)/element_types.o $(OBJDIR)/kinds.o $(OBJDIR)/materials.o
